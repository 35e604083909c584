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
use crate::query::{Match, MatchVolumes, QuerySet};

/// Owner of a volume left over.
const FREE: u32 = u32::MAX;
/// Owner of a volume taken by a candidate added during the current search.
const TAKEN: u32 = FREE - 1;
/// Hexahedra a repair may drop, by deepening step (on Armadillo `--any` the largest
/// repair needed drops 9).
const DROPS: [usize; 5] = [1, 2, 4, 8, 16];
/// Search nodes per deepening step.
const NODES: usize = 2_000;

/// The volume index of every dart and a dart of each volume.
pub(crate) struct VolumeIds {
    /// Per raw dart index, its volume (`FREE` for dead darts).
    pub of_dart: Vec<u32>,
    /// A dart of each volume.
    pub first_dart: Vec<Dart>,
}

impl VolumeIds {
    pub(crate) fn of(map: &CMap3) -> VolumeIds {
        let mut of_dart = vec![FREE; map.dart_capacity()];
        let mut walker = OrbitWalker::new();
        let mut first_dart = Vec::new();
        for (v, d) in map.cells(Orbit::Volume).enumerate() {
            for x in walker.collect(map, d, Orbit::Volume) {
                of_dart[x.idx()] = v as u32;
            }
            first_dart.push(d);
        }
        VolumeIds { of_dart, first_dart }
    }
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
    candidates: &'a [Match],
    /// The volumes of each candidate (from the matching).
    cand_vols: &'a MatchVolumes,
    /// The volumes sharing a face with each volume (CSR).
    adjacent_at: Vec<u32>,
    adjacent: Vec<u32>,
    /// Visit stamps of volumes (ball searches).
    seen: Vec<u32>,
    stamp: u32,
    /// Selected hexahedron owning each volume, `FREE` or `TAKEN`.
    owner: Vec<u32>,
    /// The candidate of each selected hexahedron (`FREE` once dropped).
    hex_cand: Vec<u32>,
    /// Candidates by the volume of their start dart (CSR).
    start_offsets: Vec<u32>,
    by_start: Vec<u32>,
    /// Faces between the start volume of a candidate and its farthest volume, at most.
    reach: usize,
    /// Whether the candidates starting in each volume are in `by_volume`.
    indexed: Vec<bool>,
    /// Candidates by the volumes they contain, for the start volumes indexed so far.
    by_volume: Vec<Vec<u32>>,
    /// Whether `by_volume[v]` holds every candidate containing v, best score first.
    complete: Vec<bool>,
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
    /// The volumes of candidate `c`, sorted.
    fn known_vols(&self, c: u32) -> &[u32] {
        self.cand_vols.of(c as usize)
    }

    /// Makes `by_volume[v]` the candidates containing volume `v`, best score first.
    fn index_containing(&mut self, v: u32) {
        if self.complete[v as usize] {
            return;
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
                for &w in self.cand_vols.of(c as usize) {
                    self.by_volume[w as usize].push(c);
                }
            }
        }
        let candidates = self.candidates;
        let score = |c: &u32| candidates[*c as usize].score;
        self.by_volume[v as usize].sort_unstable_by(|a, b| score(b).total_cmp(&score(a)).then(a.cmp(b)));
        self.complete[v as usize] = true;
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
        let mut best: Option<(u32, usize)> = None;
        for i in 0..self.debt.len() {
            let v = self.debt[i];
            if self.owner[v as usize] != FREE {
                continue;
            }
            self.index_containing(v);
            // Counting stops at 3: what matters is finding the volumes with no
            // usable candidate (the search fails) or one (no choice to make).
            let bound = best.map_or(3, |b| b.1);
            let mut usable = 0;
            for &c in &self.by_volume[v as usize] {
                if self.drops_of(c).is_some() {
                    usable += 1;
                    if usable >= bound {
                        break;
                    }
                }
            }
            if best.is_none() || usable < bound {
                best = Some((v, usable));
                if usable == 0 {
                    break;
                }
            }
        }
        best.map(|(v, _)| {
            let mut usable: Vec<(usize, u32)> = self.by_volume[v as usize]
                .iter()
                .enumerate()
                .filter_map(|(rank, &c)| self.drops_of(c).map(|d| (d.len() * 1_000_000 + rank, c)))
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
                for i in 0..self.known_vols(self.hex_cand[h as usize]).len() {
                    let x = self.known_vols(self.hex_cand[h as usize])[i];
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
    fn apply(&mut self) -> usize {
        for &h in &self.dropped {
            self.hex_cand[h as usize] = FREE;
        }
        for &c in &self.added {
            let h = self.hex_cand.len() as u32;
            for &v in self.cand_vols.of(c as usize) {
                self.owner[v as usize] = h;
            }
            self.hex_cand.push(c);
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
    cand_vols: &MatchVolumes,
    volumes: &VolumeIds,
    chosen: &mut Vec<usize>,
    effort: f64,
) -> Repaired {
    let covered: usize = chosen.iter().map(|&c| cand_vols.of(c).len()).sum();
    let (volume, dart_of) = (&volumes.of_dart, &volumes.first_dart);
    let nv = dart_of.len();
    if covered == nv {
        return Repaired { repairs: 0, tets: 0 };
    }
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
    let (adjacent_at, adjacent) = volume_adjacency(map, volume, dart_of);
    let mut r = Repair {
        candidates,
        cand_vols,
        adjacent_at,
        adjacent,
        seen: vec![0; nv],
        stamp: 0,
        owner: vec![FREE; nv],
        hex_cand: Vec::new(),
        start_offsets,
        by_start,
        reach: set.queries.iter().map(|q| q.reach()).max().unwrap_or(0),
        indexed: vec![false; nv],
        complete: vec![false; nv],
        by_volume: vec![Vec::new(); nv],
        added: Vec::new(),
        dropped: Vec::new(),
        debt: Vec::new(),
        log: Vec::new(),
        nodes: 0,
        node_limit: 0,
        drop_limit: 0,
        limited: std::cell::Cell::new(false),
    };
    r.hex_cand = chosen.iter().map(|&c| c as u32).collect();
    for (h, &c) in chosen.iter().enumerate() {
        cand_vols.of(c).iter().for_each(|&v| r.owner[v as usize] = h as u32);
    }
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
                done.tets += r.apply();
                done.repairs += 1;
            }
            r.clear_search();
        }
    }
    chosen.clear();
    chosen.extend(r.hex_cand.iter().filter(|&&c| c != FREE).map(|&c| c as usize));
    done
}
