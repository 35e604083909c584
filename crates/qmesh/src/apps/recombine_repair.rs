//! Repairing a selection of hexahedra where it leaves tetrahedra over. Best-first
//! selection (2025 §5.2.2) can take a well-shaped hexahedron W made of parts of two
//! others A and B, and leave the rest of A over. Taking A back drops W, whose other
//! part must then be covered by a candidate that may drop further hexahedra, and so
//! on: an ejection tree. The search starts from a tetrahedron left over, keeps the
//! volumes freed by dropped hexahedra as a debt, always covers next the debt volume
//! with the fewest candidates (the most constrained, as in exact cover), and stops
//! when the debt is paid: the tetrahedron is covered, every freed volume too, and
//! maybe other tetrahedra left over. The change is applied; a search that exceeds
//! its drop or node bound is undone. Bounds grow by iterative deepening, so the
//! smallest repair is found first, and a global bound (the effort, in search nodes
//! per candidate) keeps the pass proportional to the number of candidates on real
//! meshes, where most leftovers cannot be covered.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use crate::cmap::{CMap3, Dart, Orbit, OrbitWalker};
use crate::query::{Annotator, Match, QuerySet, Selected};

/// Owner of a volume left over.
const FREE: u32 = u32::MAX;
/// Owner of a volume taken by a candidate added during the current search.
const TAKEN: u32 = FREE - 1;
/// Hexahedra a repair may drop, by deepening step (on Armadillo `--any` the largest
/// repair needed drops 9).
const DROPS: [usize; 5] = [1, 2, 4, 8, 16];
/// Search nodes per deepening step.
const NODES: usize = 2_000;

/// The volume index of every dart (`FREE` for dead darts) and a dart of each volume.
pub(crate) fn volume_ids(map: &CMap3) -> (Vec<u32>, Vec<Dart>) {
    let mut id = vec![FREE; map.dart_capacity()];
    let mut walker = OrbitWalker::new();
    let mut first = Vec::new();
    for (v, d) in map.cells(Orbit::Volume).enumerate() {
        for x in walker.collect(map, d, Orbit::Volume) {
            id[x.idx()] = v as u32;
        }
        first.push(d);
    }
    (id, first)
}

/// The volumes sharing a face with each volume (`firsts[v]` a dart of volume v), as
/// offsets and a flat list.
fn volume_adjacency(map: &CMap3, volume: &[u32], firsts: &[Dart]) -> (Vec<u32>, Vec<u32>) {
    let mut walker = OrbitWalker::new();
    let mut at = Vec::with_capacity(firsts.len() + 1);
    let mut adjacent = Vec::with_capacity(4 * firsts.len());
    at.push(0);
    for &d in firsts {
        let start = adjacent.len();
        for x in walker.collect(map, d, Orbit::Volume) {
            if let Some(w) = map.beta(*x, 3).map(|o| volume[o.idx()])
                && !adjacent[start..].contains(&w)
            {
                adjacent.push(w);
            }
        }
        at.push(adjacent.len() as u32);
    }
    (at, adjacent)
}

/// The selection as an owner per volume, the search state, and lazily filled caches.
struct Repair<'a> {
    map: &'a CMap3,
    set: &'a QuerySet,
    candidates: &'a [Match],
    volume: Vec<u32>,
    /// The volumes sharing a face with each volume (CSR).
    adjacent_at: Vec<u32>,
    adjacent: Vec<u32>,
    /// Visit stamps of volumes (ball searches).
    seen: Vec<u32>,
    stamp: u32,
    /// Selected hexahedron owning each volume, `FREE` or `TAKEN`.
    owner: Vec<u32>,
    /// Volumes of each selected hexahedron.
    hex_vols: Vec<Vec<u32>>,
    /// Candidates by the volume of their start dart (CSR).
    start_offsets: Vec<u32>,
    by_start: Vec<u32>,
    /// Faces between the start volume of a candidate and its farthest volume, at most.
    reach: usize,
    /// Where the volumes of each candidate looked at so far are in `arena`
    /// (`FREE`: not looked at): their count, then the sorted volumes.
    cand_at: Vec<u32>,
    arena: Vec<u32>,
    /// Whether the candidates starting in each volume are in `by_volume`.
    indexed: Vec<bool>,
    /// Candidates by the volumes they contain, for the start volumes indexed so far.
    by_volume: Vec<Vec<u32>>,
    /// Where the candidates containing each volume looked at are in `cont_arena`.
    containing: FxHashMap<u32, (u32, u32)>,
    cont_arena: Vec<u32>,
    annot: Annotator,
    // The current search.
    added: Vec<u32>,
    dropped: Vec<u32>,
    debt: Vec<u32>,
    /// Undo log of `owner`.
    log: Vec<(u32, u32)>,
    nodes: usize,
    node_limit: usize,
    drop_limit: usize,
    /// Whether the drop limit turned a candidate down in the current search.
    limited: std::cell::Cell<bool>,
}

impl Repair<'_> {
    fn vols_of_darts(&self, darts: &[Dart]) -> Vec<u32> {
        let mut v: Vec<u32> = darts.iter().map(|d| self.volume[d.idx()]).collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// The volumes of candidate `c`, sorted.
    fn cand_vols(&mut self, c: u32) -> &[u32] {
        if self.cand_at[c as usize] == FREE {
            let darts = self.set.darts_of(self.map, &self.candidates[c as usize], &mut self.annot);
            let vols = self.vols_of_darts(&darts);
            self.cand_at[c as usize] = self.arena.len() as u32;
            self.arena.push(vols.len() as u32);
            self.arena.extend(vols);
        }
        self.known_vols(c)
    }

    /// The volumes of a candidate [`cand_vols`](Self::cand_vols) has looked at.
    fn known_vols(&self, c: u32) -> &[u32] {
        let at = self.cand_at[c as usize] as usize;
        &self.arena[at + 1..at + 1 + self.arena[at] as usize]
    }

    /// The candidates containing volume `v`, best score first (their volumes known).
    fn containing(&mut self, v: u32) -> std::ops::Range<usize> {
        if let Some(&(a, b)) = self.containing.get(&v) {
            return a as usize..b as usize;
        }
        self.stamp += 1;
        let mut ball = vec![v];
        self.seen[v as usize] = self.stamp;
        let mut layer = 0..1;
        for _ in 0..self.reach {
            let next = ball.len();
            for i in layer.clone() {
                for k in self.adjacent_at[ball[i] as usize]..self.adjacent_at[ball[i] as usize + 1] {
                    let w = self.adjacent[k as usize];
                    if self.seen[w as usize] != self.stamp {
                        self.seen[w as usize] = self.stamp;
                        ball.push(w);
                    }
                }
            }
            layer = next..ball.len();
        }
        // Every candidate containing v starts in the ball: index the candidates of
        // each start volume there by their volumes (once per start volume), and the
        // list of v is complete.
        for u in ball {
            if std::mem::replace(&mut self.indexed[u as usize], true) {
                continue;
            }
            for k in self.start_offsets[u as usize]..self.start_offsets[u as usize + 1] {
                let c = self.by_start[k as usize];
                for i in 0..self.cand_vols(c).len() {
                    let w = self.known_vols(c)[i];
                    self.by_volume[w as usize].push(c);
                }
            }
        }
        let mut out = std::mem::take(&mut self.by_volume[v as usize]);
        let score = |c: &u32| self.candidates[*c as usize].score;
        out.sort_unstable_by(|a, b| score(b).total_cmp(&score(a)).then(a.cmp(b)));
        let a = self.cont_arena.len();
        self.cont_arena.extend(out);
        self.containing.insert(v, (a as u32, self.cont_arena.len() as u32));
        a..self.cont_arena.len()
    }

    fn set_owner(&mut self, v: u32, o: u32) {
        self.log.push((v, self.owner[v as usize]));
        self.owner[v as usize] = o;
    }

    /// The selected hexahedra candidate `c` would drop, or None if it meets a volume
    /// taken in this search or drops more than allowed.
    fn drops_of(&self, c: u32) -> Option<SmallVec<[u32; 4]>> {
        let room = self.drop_limit - self.dropped.len();
        let mut drops = SmallVec::new();
        for &v in self.known_vols(c) {
            match self.owner[v as usize] {
                FREE => {}
                TAKEN => return None,
                h if drops.contains(&h) => {}
                h => {
                    if drops.len() == room {
                        self.limited.set(true);
                        return None;
                    }
                    drops.push(h);
                }
            }
        }
        Some(drops)
    }

    /// The debt volume with the fewest usable candidates (up to 3) and those candidates (fewest
    /// drops first, then best score); None once the debt is paid.
    fn most_constrained(&mut self) -> Option<(u32, Vec<u32>)> {
        let mut best: Option<(u32, std::ops::Range<usize>, usize)> = None;
        for i in 0..self.debt.len() {
            let v = self.debt[i];
            if self.owner[v as usize] != FREE {
                continue;
            }
            let range = self.containing(v);
            // Counting stops at 3: what matters is finding the volumes with no
            // usable candidate (the search fails) or one (no choice to make).
            let bound = best.as_ref().map_or(3, |b| b.2);
            let mut usable = 0;
            for k in range.clone() {
                if self.drops_of(self.cont_arena[k]).is_some() {
                    usable += 1;
                    if usable >= bound {
                        break;
                    }
                }
            }
            if best.is_none() || usable < bound {
                best = Some((v, range, usable));
                if usable == 0 {
                    break;
                }
            }
        }
        best.map(|(v, range, _)| {
            let mut usable: Vec<(usize, u32)> = range
                .enumerate()
                .filter_map(|(rank, k)| {
                    let c = self.cont_arena[k];
                    self.drops_of(c).map(|d| (d.len() * 1_000_000 + rank, c))
                })
                .collect();
            usable.sort_unstable();
            (v, usable.into_iter().map(|(_, c)| c).collect())
        })
    }

    /// Covers the debt; on success the search state holds the repair.
    fn search(&mut self) -> bool {
        if self.nodes >= self.node_limit {
            return false;
        }
        self.nodes += 1;
        let Some((_, options)) = self.most_constrained() else { return true };
        for c in options {
            let Some(drops) = self.drops_of(c) else { continue };
            let (log, debt, dropped) = (self.log.len(), self.debt.len(), self.dropped.len());
            for h in drops {
                for i in 0..self.hex_vols[h as usize].len() {
                    let x = self.hex_vols[h as usize][i];
                    self.set_owner(x, FREE);
                    self.debt.push(x);
                }
                self.dropped.push(h);
            }
            for i in 0..self.known_vols(c).len() {
                self.set_owner(self.known_vols(c)[i], TAKEN);
            }
            self.added.push(c);
            if self.search() {
                return true;
            }
            self.added.pop();
            self.dropped.truncate(dropped);
            self.debt.truncate(debt);
            while self.log.len() > log {
                let (v, o) = self.log.pop().expect("log is longer than its mark");
                self.owner[v as usize] = o;
            }
        }
        false
    }
}

impl Repair<'_> {
    fn clear_search(&mut self) {
        self.added.clear();
        self.dropped.clear();
        self.debt.clear();
        self.log.clear();
    }

    /// Makes the repair found by [`search`](Self::search) part of the selection;
    /// returns the tetrahedra left over that it covers.
    fn apply(&mut self, slots: &mut Vec<Option<Selected>>) -> usize {
        for &h in &self.dropped {
            slots[h as usize] = None;
            self.hex_vols[h as usize].clear();
        }
        for &c in &self.added {
            let h = slots.len() as u32;
            let m = self.candidates[c as usize];
            slots.push(Some(Selected { m, darts: self.set.darts_of(self.map, &m, &mut self.annot) }));
            let vols = self.known_vols(c).to_vec();
            vols.iter().for_each(|&v| self.owner[v as usize] = h);
            self.hex_vols.push(vols);
        }
        // A volume whose first change came from FREE was left over.
        let mut first: FxHashMap<u32, u32> = FxHashMap::default();
        for &(v, o) in &self.log {
            first.entry(v).or_insert(o);
        }
        first.values().filter(|&&o| o == FREE).count()
    }
}

/// What [`repair_leftovers`] did.
pub(crate) struct Repaired {
    /// Repairs applied.
    pub repairs: usize,
    /// Tetrahedra left over before that are now in a hexahedron.
    pub tets: usize,
}

/// Repairs `chosen` (matches of `set` on `map` among `candidates`, without overlap)
/// where it leaves tetrahedra over, searching at most `effort` nodes per candidate
/// in all.
pub(crate) fn repair_leftovers(
    map: &CMap3,
    set: &QuerySet,
    candidates: &[Match],
    chosen: &mut Vec<Selected>,
    effort: f64,
) -> Repaired {
    let covered: usize = chosen.iter().map(|s| set.queries[s.m.query as usize].nb_volumes()).sum();
    let tets = map.cells(Orbit::Volume).count();
    if covered == tets {
        return Repaired { repairs: 0, tets: 0 };
    }
    let (volume, dart_of) = volume_ids(map);
    let nv = dart_of.len();
    let mut start_offsets = vec![0u32; nv + 1];
    candidates.iter().for_each(|m| start_offsets[volume[m.start.idx()] as usize + 1] += 1);
    for i in 0..nv {
        start_offsets[i + 1] += start_offsets[i];
    }
    let mut fill = start_offsets.clone();
    let mut by_start = vec![0u32; candidates.len()];
    for (i, m) in candidates.iter().enumerate() {
        let v = volume[m.start.idx()] as usize;
        by_start[fill[v] as usize] = i as u32;
        fill[v] += 1;
    }
    let (adjacent_at, adjacent) = volume_adjacency(map, &volume, &dart_of);
    let mut r = Repair {
        map,
        set,
        candidates,
        volume,
        adjacent_at,
        adjacent,
        seen: vec![0; nv],
        stamp: 0,
        owner: vec![FREE; nv],
        hex_vols: Vec::new(),
        start_offsets,
        by_start,
        reach: set.queries.iter().map(|q| q.reach()).max().unwrap_or(0),
        cand_at: vec![FREE; candidates.len()],
        arena: Vec::new(),
        containing: FxHashMap::default(),
        cont_arena: Vec::new(),
        indexed: vec![false; nv],
        by_volume: vec![Vec::new(); nv],
        annot: set.annotator(),
        added: Vec::new(),
        dropped: Vec::new(),
        debt: Vec::new(),
        log: Vec::new(),
        nodes: 0,
        node_limit: 0,
        drop_limit: 0,
        limited: std::cell::Cell::new(false),
    };
    r.hex_vols = chosen.iter().map(|s| r.vols_of_darts(&s.darts)).collect();
    for (h, vs) in r.hex_vols.iter().enumerate() {
        vs.iter().for_each(|&v| r.owner[v as usize] = h as u32);
    }
    let mut slots: Vec<Option<Selected>> = chosen.drain(..).map(Some).collect();
    let mut done = Repaired { repairs: 0, tets: 0 };
    let mut pass_nodes = (effort * candidates.len() as f64) as usize;
    // Leftovers whose search failed with neither bound reached: no deeper search helps.
    let mut hopeless = vec![false; nv];
    'deepen: for drop_limit in DROPS {
        for v0 in 0..nv as u32 {
            if r.owner[v0 as usize] != FREE || hopeless[v0 as usize] {
                continue;
            }
            if pass_nodes == 0 {
                break 'deepen;
            }
            (r.nodes, r.node_limit, r.drop_limit) = (0, NODES.min(pass_nodes), drop_limit);
            r.debt.push(v0);
            r.limited.set(false);
            let found = r.search();
            pass_nodes -= r.nodes;
            hopeless[v0 as usize] = !found && !r.limited.get() && r.nodes < r.node_limit;
            if found {
                done.tets += r.apply(&mut slots);
                done.repairs += 1;
            }
            r.clear_search();
        }
    }
    chosen.extend(slots.into_iter().flatten());
    done
}
