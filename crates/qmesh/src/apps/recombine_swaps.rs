//! Improving a best-first selection of hexahedra by augmenting chains. Best-first
//! selection (2025 §5.2.2) can take a well-shaped hexahedron W made of halves of two
//! others A and B; when the other half of A is left over, exchanging W for A frees the
//! half of B that W held, which may complete B with tetrahedra left over, or free half
//! of the next hexahedron, and so on. A chain that ends on tetrahedra left over gives
//! one hexahedron more than it takes: it is applied; any other is undone.

use rustc_hash::FxHashMap;

use crate::cmap::{CMap3, Dart, Orbit};
use crate::query::{Match, QuerySet, Selected};

const FREE: u32 = u32::MAX;
/// Exchanges per chain at most (a chain of k exchanges turns k hexahedra into k + 1).
const MAX_CHAIN: usize = 4;
/// Layers of selected hexahedra around the tetrahedra left over whose candidates are
/// considered (on Armadillo `--any`: 1 layer gives 29,930 of 29,935 hexahedra with 40k
/// candidates replayed, 2 layers 29,933 with 99k, at +0.3 s and +25 MB).
const LAYERS: usize = 1;
/// Candidates tried per chain search: bounds the search on real meshes, where many
/// tetrahedra are left and chains rarely close (HexMe cube: select 3.1 s and 14.8 %
/// tets left unbounded; 1.8 s and 19 % with 256; 1.2 s and 25 % with 64).
const BUDGET: usize = 256;

/// The volume index of every dart (`u32::MAX` for dead darts) and the volume count.
fn volume_ids(map: &CMap3) -> (Vec<u32>, usize) {
    let mut id = vec![FREE; map.dart_capacity()];
    let mut walker = crate::cmap::OrbitWalker::new();
    let mut n = 0;
    for (v, d) in map.cells(Orbit::Volume).enumerate() {
        for x in walker.collect(map, d, Orbit::Volume) {
            id[x.idx()] = v as u32;
        }
        n = v + 1;
    }
    (id, n)
}

/// The search state: which selected hexahedron owns each volume, and candidate volumes.
struct Chains<'a> {
    owner: Vec<u32>,
    /// Candidates near the tetrahedra left over: index into the candidate list, volumes.
    cands: Vec<(usize, Vec<u32>)>,
    containing: FxHashMap<u32, Vec<u32>>,
    candidates: &'a [Match],
    /// Undo log of `owner` changes.
    log: Vec<(u32, u32)>,
    /// Candidates a chain search may still try (reset per starting volume).
    budget: usize,
}

/// A move of a chain: selected hexahedron `dropped` (or `FREE` for the final addition)
/// gives way to candidate `added` (index into `cands`).
type Move = (u32, usize);

impl Chains<'_> {
    fn set(&mut self, v: u32, o: u32) {
        self.log.push((v, self.owner[v as usize]));
        self.owner[v as usize] = o;
    }

    fn undo_to(&mut self, len: usize) {
        while self.log.len() > len {
            let (v, o) = self.log.pop().expect("log is longer than len");
            self.owner[v as usize] = o;
        }
    }

    /// The selected hexahedra a candidate overlaps (None if a volume is taken by this chain).
    fn owners(&self, c: usize, taken: u32) -> Option<Vec<u32>> {
        let mut o: Vec<u32> = Vec::new();
        for &v in &self.cands[c].1 {
            match self.owner[v as usize] {
                FREE => {}
                x if x == taken => return None,
                x => {
                    if !o.contains(&x) {
                        o.push(x);
                    }
                }
            }
        }
        Some(o)
    }

    /// Extends a chain whose last exchange freed `freed`: candidates on a freed
    /// volume that overlap at most one selected hexahedron.
    fn extend(&mut self, freed: &[u32], chain: &mut Vec<Move>, vols_of: &dyn Fn(u32) -> Vec<u32>) -> bool {
        const TAKEN: u32 = FREE - 1;
        let mut options: Vec<u32> =
            freed.iter().flat_map(|v| self.containing.get(v).cloned().unwrap_or_default()).collect();
        options.sort_unstable_by(|&a, &b| {
            let (sa, sb) =
                (self.candidates[self.cands[a as usize].0].score, self.candidates[self.cands[b as usize].0].score);
            sb.total_cmp(&sa).then(a.cmp(&b))
        });
        options.dedup();
        for c in options {
            if self.budget == 0 {
                return false;
            }
            self.budget -= 1;
            let c = c as usize;
            let Some(owners) = self.owners(c, TAKEN) else { continue };
            if owners.len() > 1 || chain.iter().any(|m| m.1 == c) {
                continue;
            }
            let mark = self.log.len();
            let vols = self.cands[c].1.clone();
            match owners.first() {
                None => {
                    vols.iter().for_each(|&v| self.set(v, TAKEN));
                    chain.push((FREE, c));
                    return true;
                }
                Some(&h) if chain.len() < MAX_CHAIN => {
                    let hv = vols_of(h);
                    hv.iter().for_each(|&v| self.set(v, FREE));
                    vols.iter().for_each(|&v| self.set(v, TAKEN));
                    let next: Vec<u32> = hv.iter().copied().filter(|v| self.owner[*v as usize] == FREE).collect();
                    chain.push((h, c));
                    if self.extend(&next, chain, vols_of) {
                        return true;
                    }
                    chain.pop();
                }
                _ => {}
            }
            self.undo_to(mark);
        }
        false
    }
}

/// Applies augmenting chains to `chosen` (matches of `set` on `map` among
/// `candidates`) until none is found; returns the number of hexahedra gained.
pub(crate) fn improve_by_swaps(map: &CMap3, set: &QuerySet, candidates: &[Match], chosen: &mut Vec<Selected>) -> usize {
    let (volume, nv) = volume_ids(map);
    let vols_of_darts = |darts: &[Dart]| -> Vec<u32> {
        let mut v: Vec<u32> = darts.iter().map(|d| volume[d.idx()]).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let mut chosen_vols: Vec<Vec<u32>> = chosen.iter().map(|s| vols_of_darts(&s.darts)).collect();
    let mut owner = vec![FREE; nv];
    for (i, vs) in chosen_vols.iter().enumerate() {
        vs.iter().for_each(|&v| owner[v as usize] = i as u32);
    }
    // Hot volumes: left over, and selected hexahedra up to LAYERS steps away.
    let mut hot = vec![false; nv];
    let mut frontier: Vec<u32> = (0..nv as u32).filter(|&v| owner[v as usize] == FREE).collect();
    if frontier.is_empty() {
        return 0;
    }
    frontier.iter().for_each(|&v| hot[v as usize] = true);
    let mut in_frontier = vec![false; nv];
    for _ in 0..LAYERS {
        in_frontier.iter_mut().for_each(|x| *x = false);
        frontier.iter().for_each(|&v| in_frontier[v as usize] = true);
        let mut next = Vec::new();
        for d in map.darts() {
            if in_frontier[volume[d.idx()] as usize] {
                let Some(o) = map.beta(d, 3) else { continue };
                let h = owner[volume[o.idx()] as usize];
                if h != FREE && !hot[volume[o.idx()] as usize] {
                    for &w in &chosen_vols[h as usize] {
                        if !hot[w as usize] {
                            hot[w as usize] = true;
                            next.push(w);
                        }
                    }
                }
            }
        }
        frontier = next;
    }
    let mut annot = set.annotator();
    let mut chains =
        Chains { owner, cands: Vec::new(), containing: FxHashMap::default(), candidates, log: Vec::new(), budget: 0 };
    for (i, m) in candidates.iter().enumerate() {
        if hot[volume[m.start.idx()] as usize] {
            let vs = vols_of_darts(&set.darts_of(map, m, &mut annot));
            for &v in &vs {
                chains.containing.entry(v).or_default().push(chains.cands.len() as u32);
            }
            chains.cands.push((i, vs));
        }
    }
    let mut gained = 0;
    loop {
        let left: Vec<u32> = (0..nv as u32).filter(|&v| hot[v as usize] && chains.owner[v as usize] == FREE).collect();
        let mut changed = false;
        for v in left {
            if chains.owner[v as usize] != FREE {
                continue;
            }
            let mut chain = Vec::new();
            chains.log.clear();
            chains.budget = BUDGET;
            let found = {
                let vols_of = |h: u32| chosen_vols[h as usize].clone();
                chains.extend(&[v], &mut chain, &vols_of)
            };
            if !found {
                chains.undo_to(0);
                continue;
            }
            // Apply: each dropped hexahedron's slot takes the candidate that replaced it.
            for &(h, c) in &chain {
                let (ci, vs) = chains.cands[c].clone();
                let m = candidates[ci];
                let sel = Selected { m, darts: set.darts_of(map, &m, &mut annot) };
                let slot = if h == FREE { chosen.len() } else { h as usize };
                if slot == chosen.len() {
                    chosen.push(sel);
                    chosen_vols.push(vs.clone());
                } else {
                    chosen[slot] = sel;
                    chosen_vols[slot] = vs.clone();
                }
                vs.iter().for_each(|&w| chains.owner[w as usize] = slot as u32);
            }
            gained += 1;
            changed = true;
        }
        if !changed {
            return gained;
        }
    }
}
