//! Improving a greedy selection of hexahedra by swaps: a selected hexahedron whose
//! tetrahedra, with tetrahedra left over around it, hold two other candidates that do
//! not overlap is exchanged for those two (one hexahedron more, each time). Best-first
//! selection (2025 §5.2.2) can take a well-shaped hexahedron straddling two others; this
//! gives them back.

use rustc_hash::FxHashMap;

use crate::cmap::{CMap3, Dart, Orbit};
use crate::query::{Match, QuerySet, Selected};

const FREE: u32 = u32::MAX;

/// The volume index of every dart (`u32::MAX` for dead darts).
fn volume_ids(map: &CMap3) -> Vec<u32> {
    let mut id = vec![FREE; map.dart_capacity()];
    let mut walker = crate::cmap::OrbitWalker::new();
    for (v, d) in map.cells(Orbit::Volume).enumerate() {
        for x in walker.collect(map, d, Orbit::Volume) {
            id[x.idx()] = v as u32;
        }
    }
    id
}

/// Swaps in `chosen` (matches of `set` on `map` among `candidates`) until no selected
/// hexahedron can be exchanged for two; returns the number of swaps.
pub(crate) fn improve_by_swaps(map: &CMap3, set: &QuerySet, candidates: &[Match], chosen: &mut Vec<Selected>) -> usize {
    let volume = volume_ids(map);
    let nv = volume.iter().filter(|&&v| v != FREE).map(|&v| v as usize + 1).max().unwrap_or(0);
    let mut owner = vec![FREE; nv];
    let vols_of = |darts: &[Dart]| -> Vec<u32> {
        let mut v: Vec<u32> = darts.iter().map(|d| volume[d.idx()]).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let mut chosen_vols: Vec<Vec<u32>> = chosen.iter().map(|s| vols_of(&s.darts)).collect();
    for (i, vs) in chosen_vols.iter().enumerate() {
        vs.iter().for_each(|&v| owner[v as usize] = i as u32);
    }
    let mut annot = set.annotator();
    let mut swaps = 0;
    loop {
        // Hot volumes: left over, or in a selected hexahedron next to one left over.
        let mut hot = vec![false; nv];
        for d in map.darts() {
            let v = volume[d.idx()];
            if owner[v as usize] != FREE {
                continue;
            }
            hot[v as usize] = true;
            if let Some(o) = map.beta(d, 3) {
                let h = owner[volume[o.idx()] as usize];
                if h != FREE {
                    chosen_vols[h as usize].iter().for_each(|&w| hot[w as usize] = true);
                }
            }
        }
        // Candidates inside the hot region overlapping at most one selected hexahedron.
        let mut by_owner: FxHashMap<u32, Vec<(usize, Vec<u32>)>> = FxHashMap::default();
        for (i, m) in candidates.iter().enumerate() {
            if !hot[volume[m.start.idx()] as usize] {
                continue;
            }
            let vs = vols_of(&set.darts_of(map, m, &mut annot));
            let mut owners: Vec<u32> = vs.iter().map(|&v| owner[v as usize]).filter(|&o| o != FREE).collect();
            owners.dedup();
            owners.sort_unstable();
            owners.dedup();
            if owners.len() <= 1 && vs.iter().any(|&v| owner[v as usize] == FREE) {
                by_owner.entry(owners.first().copied().unwrap_or(FREE)).or_default().push((i, vs));
            }
        }
        for list in by_owner.values_mut() {
            list.sort_by(|a, b| candidates[b.0].score.total_cmp(&candidates[a.0].score).then(a.0.cmp(&b.0)));
        }
        let mut changed = false;
        let mut keys: Vec<u32> = by_owner.keys().copied().collect();
        keys.sort_unstable();
        for h in keys {
            let list = &by_owner[&h];
            let still = |vs: &[u32]| vs.iter().all(|&v| owner[v as usize] == h || owner[v as usize] == FREE);
            let free_only = h == FREE;
            let pick: Option<Vec<usize>> = if free_only {
                list.iter().position(|(_, vs)| still(vs)).map(|a| vec![a])
            } else {
                let ok: Vec<usize> = (0..list.len()).filter(|&a| still(&list[a].1)).collect();
                ok.iter().enumerate().find_map(|(x, &a)| {
                    ok[x + 1..].iter().find(|&&b| disjoint(&list[a].1, &list[b].1)).map(|&b| vec![a, b])
                })
            };
            let Some(pick) = pick else { continue };
            if !free_only {
                // Drop h; its slot takes the first new hexahedron.
                chosen_vols[h as usize].iter().for_each(|&v| owner[v as usize] = FREE);
            }
            for (j, &k) in pick.iter().enumerate() {
                let (ci, vs) = &list[k];
                let m = candidates[*ci];
                let sel = Selected { m, darts: set.darts_of(map, &m, &mut annot) };
                let slot = if j == 0 && !free_only { h as usize } else { chosen.len() };
                if slot == chosen.len() {
                    chosen.push(sel);
                    chosen_vols.push(vs.clone());
                } else {
                    chosen[slot] = sel;
                    chosen_vols[slot] = vs.clone();
                }
                vs.iter().for_each(|&v| owner[v as usize] = slot as u32);
            }
            swaps += 1;
            changed = true;
        }
        if !changed {
            return swaps;
        }
    }
}

fn disjoint(a: &[u32], b: &[u32]) -> bool {
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => return false,
        }
    }
    true
}
