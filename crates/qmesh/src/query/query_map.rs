//! A compiled query: the query map, its labelling and word, its automorphisms, and the
//! geometry the metrics and the modify operations need.

use super::automorphism::Automorphisms;
use super::error::QueryError;
use super::fit::AffineFit;
use super::word::{Condition, Labelling, QueryWord};
use crate::cmap::{CMap3, Dart};
use crate::geom::{cross, dot, hex_scaled_jacobian, sub};
use std::sync::OnceLock;

/// A query (2025 §5): a connected map, 1- and 2-sewn everywhere, with a boundary
/// condition on each 3-free dart.
#[derive(Clone, Debug)]
pub struct Query {
    pub name: String,
    /// The query map and its labelling, built now or on first use.
    source: Source,
    pub word: QueryWord,
    pub automorphisms: Automorphisms,
    /// Faces of each volume as cycles of labels (volume metric), computed on first use.
    volumes: OnceLock<Vec<Vec<Vec<u32>>>>,
    /// See [`Query::volume_labels`].
    volume_labels: OnceLock<Vec<u32>>,
    /// Labels of darts at the 8 extreme corners in VTK hexahedron order, when the
    /// query's own geometry spans a positive hexahedron (hex-quality metric).
    pub corners: Option<[u32; 8]>,
    /// Among automorphic images of a match, keep the one whose geometry fits the
    /// query best (instead of the one starting at the smallest dart).
    pub orient_by_geometry: bool,
    /// Reject matches whose best affine fit from the query leaves a relative residual
    /// above this (0 = an affine copy of the query; see `fit.rs`).
    pub max_residual: Option<f64>,
    /// The affine-fit data, computed on first use (most rule books never need it).
    fit: OnceLock<Option<AffineFit>>,
}

/// A query reads as its word (for the prefix tree, which keeps no copy of the words).
impl AsRef<QueryWord> for Query {
    fn as_ref(&self) -> &QueryWord {
        &self.word
    }
}

/// Rebuilds a stored query's map: the map and the start dart of its labelling, from a
/// key the query keeps (a class index for the recombination rules).
pub(crate) type RebuildMap = fn(u32) -> (CMap3, Dart);

/// Where a query's map comes from: given, or rebuilt on first use by `rebuild(key)`
/// (the map and its start dart) for queries stored compiled, whose matching needs only
/// their word (rule books of hundreds of queries, most of which no match uses).
#[derive(Clone, Debug)]
struct Source {
    built: OnceLock<(CMap3, Labelling)>,
    rebuild: Option<(RebuildMap, u32)>,
}

impl Source {
    fn get(&self) -> &(CMap3, Labelling) {
        self.built.get_or_init(|| {
            let (build, key) = self.rebuild.expect("a query has its map or a way to rebuild it");
            let (map, start) = build(key);
            let labelling = Labelling::new(&map, start).expect("stored queries rebuild as they were compiled");
            (map, labelling)
        })
    }
}

impl Query {
    /// Compiles `map` into a query, labelled from its first dart, with `condition(d)`
    /// for each 3-free dart.
    ///
    /// # Errors
    /// A map that is invalid, empty, not connected, 1- or 2-free somewhere, or larger
    /// than [`MAX_QUERY_DARTS`](super::MAX_QUERY_DARTS).
    pub fn new(name: &str, map: CMap3, condition: impl FnMut(Dart) -> Condition) -> Result<Query, QueryError> {
        let start = map.darts().next().ok_or(QueryError::Empty)?;
        Self::from_start(name, map, start, condition)
    }

    /// As [`new`](Self::new), labelled from `start`.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn from_start(
        name: &str,
        map: CMap3,
        start: Dart,
        condition: impl FnMut(Dart) -> Condition,
    ) -> Result<Query, QueryError> {
        if let Some(v) = map.is_valid().first() {
            return Err(QueryError::Invalid(v.to_string()));
        }
        Self::compile(name, map, start, condition, None::<fn(&CMap3, &Labelling) -> [u32; 8]>, None)
    }

    /// As [`from_start`](Self::from_start) without checking the map's validity, for the
    /// maps qmesh builds itself (rule books of hundreds of queries, whose validity their
    /// tests assert), with the hexahedral corners given by `corners(map, labelling)`
    /// (see [`set_corners`](Self::set_corners)) instead of found from the geometry, and
    /// the automorphisms, when `automorphism_starts` is given, computed only from those
    /// labels (stored from an earlier search).
    #[cfg(test)]
    pub(crate) fn from_valid_start_with_corners(
        name: &str,
        map: CMap3,
        start: Dart,
        condition: impl FnMut(Dart) -> Condition,
        corners: impl FnOnce(&CMap3, &Labelling) -> [u32; 8],
        automorphism_starts: Option<&[u32]>,
    ) -> Result<Query, QueryError> {
        Self::compile(name, map, start, condition, Some(corners), automorphism_starts)
    }

    fn compile<F: FnOnce(&CMap3, &Labelling) -> [u32; 8]>(
        name: &str,
        map: CMap3,
        start: Dart,
        condition: impl FnMut(Dart) -> Condition,
        given_corners: Option<F>,
        automorphism_starts: Option<&[u32]>,
    ) -> Result<Query, QueryError> {
        if map.nb_darts() > super::MAX_QUERY_DARTS {
            return Err(QueryError::TooLarge(map.nb_darts()));
        }
        let labelling = Labelling::new(&map, start)?;
        let word = QueryWord::new(&map, &labelling, condition);
        let mut automorphisms = match automorphism_starts {
            Some(starts) => Automorphisms::from_starts(&map, &labelling, &word, starts),
            None => Automorphisms::of(&map, &labelling, &word),
        };
        let corners = match given_corners {
            Some(f) => {
                let c = f(&map, &labelling);
                automorphisms.restrict_to_corner_symmetries(&map, &labelling, &c);
                Some(c)
            }
            None => hex_corners(&map, &labelling),
        };
        let source = Source { built: OnceLock::from((map, labelling)), rebuild: None };
        Ok(Self::assemble(name.to_string(), source, word, automorphisms, corners))
    }

    /// A query stored compiled: its word, automorphisms and hexahedral corners as
    /// computed before, its map rebuilt by `rebuild(key)` (the map and the start dart
    /// of the labelling) only when something needs it (a modify plan, a volume metric).
    /// The caller guarantees that the rebuilt map's word is `word` (rule books test it).
    pub(crate) fn stored(
        name: String,
        word: QueryWord,
        automorphisms: Automorphisms,
        corners: Option<[u32; 8]>,
        rebuild: (RebuildMap, u32),
    ) -> Query {
        Self::assemble(name, Source { built: OnceLock::new(), rebuild: Some(rebuild) }, word, automorphisms, corners)
    }

    fn assemble(
        name: String,
        source: Source,
        word: QueryWord,
        automorphisms: Automorphisms,
        corners: Option<[u32; 8]>,
    ) -> Query {
        Query {
            name,
            source,
            word,
            automorphisms,
            volumes: OnceLock::new(),
            volume_labels: OnceLock::new(),
            corners,
            orient_by_geometry: false,
            max_residual: None,
            fit: OnceLock::new(),
        }
    }

    /// The query map (rebuilt on first use for stored queries).
    pub fn map(&self) -> &CMap3 {
        &self.source.get().0
    }

    /// The labelling of the query map from which [`word`](Self::word) was read.
    pub fn labelling(&self) -> &Labelling {
        &self.source.get().1
    }

    /// Replaces the word's conditions (the labelling is kept) and recomputes the
    /// automorphisms.
    pub fn set_conditions(&mut self, mut condition: impl FnMut(Dart) -> Condition) {
        let free: Vec<usize> = self.word.free_labels().collect();
        let (map, labelling) = self.source.get();
        for k in free {
            self.word.set_condition(k, condition(labelling.darts[k - 1]));
        }
        self.automorphisms = Automorphisms::of(map, labelling, &self.word);
    }

    /// Sets the hexahedral corners (labels at the VTK nodes) that the hex-quality
    /// metric and the corner guards read; automorphisms that do not move them as a cube
    /// symmetry then give matches of their own (they read another hexahedron).
    pub fn set_corners(&mut self, corners: [u32; 8]) {
        let (map, labelling) = self.source.get();
        self.automorphisms.restrict_to_corner_symmetries(map, labelling, &corners);
        self.corners = Some(corners);
    }

    /// Whether the query's vertices span 3D, so that matches can be compared with it by
    /// an affine fit (`orient_by_geometry`, `max_residual`).
    pub fn has_affine_fit(&self) -> bool {
        self.fit().is_some()
    }

    /// The affine-fit data of the query's vertices, None when they do not span 3D.
    pub(crate) fn fit(&self) -> Option<&AffineFit> {
        self.fit.get_or_init(|| vertex_fit(self.map(), self.labelling())).as_ref()
    }

    /// Faces of each volume as cycles of labels.
    fn volumes(&self) -> &[Vec<Vec<u32>>] {
        self.volumes.get_or_init(|| volume_faces(self.map(), self.labelling()))
    }

    /// The smallest label of each volume, ascending (read from the word): a match's
    /// input volumes are those of the darts annotated with these.
    pub(crate) fn volume_labels(&self) -> &[u32] {
        self.volume_labels.get_or_init(|| self.word.volume_firsts())
    }

    /// Number of darts.
    pub fn nb_darts(&self) -> usize {
        self.word.nb_darts()
    }

    /// Number of volumes.
    pub fn nb_volumes(&self) -> usize {
        self.volume_labels().len()
    }

    /// The most faces a walk from the start dart's volume crosses to reach any other
    /// volume of the query: every volume of a match lies within this many faces of
    /// the volume of its start dart.
    pub fn reach(&self) -> usize {
        let (volume, count) = self.word.volumes_of_labels();
        let mut neighbours = vec![Vec::new(); count];
        for k in 1..=self.nb_darts() {
            let other = self.word.symbol(k, 3);
            if other < super::word::FIRST_CONDITION {
                neighbours[volume[k] as usize].push(volume[other as usize]);
            }
        }
        let mut dist = vec![usize::MAX; count];
        let mut queue = std::collections::VecDeque::from([volume[1]]);
        dist[volume[1] as usize] = 0;
        while let Some(v) = queue.pop_front() {
            for &w in &neighbours[v as usize] {
                if dist[w as usize] == usize::MAX {
                    dist[w as usize] = dist[v as usize] + 1;
                    queue.push_back(w);
                }
            }
        }
        dist.into_iter().max().unwrap_or(0)
    }

    /// Sum of the signed volumes of the matched input volumes (`matched[k-1]` = input
    /// dart of label k).
    pub fn matched_volume(&self, map: &CMap3, matched: &[u32]) -> f64 {
        let p = |l: u32| map.position(map.vertex_of(Dart::from_raw(matched[l as usize - 1]).expect("matched dart")));
        let mut total = 0.0;
        for faces in self.volumes() {
            for f in faces {
                let a = p(f[0]);
                for w in f[1..].windows(2) {
                    let (b, c) = (p(w[0]), p(w[1]));
                    let (u, v, x) = (sub(b, a), sub(c, a), a);
                    // Right-hand normals of β1 cycles point into their volume (cmap/).
                    total -= dot(x, cross(u, v)) / 6.0;
                }
            }
        }
        total
    }

    /// The scaled Jacobian of the hexahedron spanned by the matched corners, or None
    /// when the query has no hexahedral corners.
    pub fn matched_hex_quality(&self, map: &CMap3, matched: &[u32]) -> Option<f64> {
        let c = self.corners?;
        let pts: [[f64; 3]; 8] = std::array::from_fn(|i| {
            map.position(map.vertex_of(Dart::from_raw(matched[c[i] as usize - 1]).expect("matched dart")))
        });
        Some(hex_scaled_jacobian(&pts))
    }
}

/// The faces of every volume of the query as label cycles (β1 order).
fn volume_faces(map: &CMap3, l: &Labelling) -> Vec<Vec<Vec<u32>>> {
    let mut seen = vec![false; map.dart_capacity()];
    let mut out = Vec::new();
    for &v in &l.darts {
        if seen[v.idx()] {
            continue;
        }
        let mut faces = Vec::new();
        for d in map.orbit(v, crate::cmap::Orbit::Volume) {
            if seen[d.idx()] {
                continue;
            }
            let mut face = Vec::new();
            let mut x = d;
            loop {
                seen[x.idx()] = true;
                face.push(l.of(x));
                x = map.next(x);
                if x == d {
                    break;
                }
            }
            faces.push(face);
        }
        out.push(faces);
    }
    out
}

/// The query's vertices extreme in the 8 diagonal directions, in VTK hexahedron order
/// (a dart label at each), if they are 8 distinct vertices spanning a positive hex.
fn hex_corners(map: &CMap3, l: &Labelling) -> Option<[u32; 8]> {
    const SIGNS: [[f64; 3]; 8] = [
        [-1., -1., -1.],
        [1., -1., -1.],
        [1., 1., -1.],
        [-1., 1., -1.],
        [-1., -1., 1.],
        [1., -1., 1.],
        [1., 1., 1.],
        [-1., 1., 1.],
    ];
    let pts: Vec<[f64; 3]> = l.darts.iter().map(|&d| map.point(d)).collect();
    let c = crate::geom::centroid(pts.iter().copied());
    // The first dart (smallest label) at each vertex: the candidates in label order.
    let mut seen = rustc_hash::FxHashSet::default();
    let firsts: Vec<usize> = (0..pts.len()).filter(|&a| seen.insert(map.vertex_of(l.darts[a]))).collect();
    let mut corners = [0u32; 8];
    let mut ids = [0u32; 8];
    for (i, s) in SIGNS.iter().enumerate() {
        // The first dart (smallest label) of largest extent along `s`.
        let mut best = (0, f64::NEG_INFINITY);
        for &a in &firsts {
            let x = dot(sub(pts[a], c), *s);
            if x.total_cmp(&best.1).is_gt() {
                best = (a, x);
            }
        }
        let best = best.0;
        corners[i] = best as u32 + 1;
        ids[i] = map.vertex_of(l.darts[best]);
    }
    let mut sorted = ids;
    sorted.sort_unstable();
    if sorted.windows(2).any(|w| w[0] == w[1]) {
        return None;
    }
    let p: [[f64; 3]; 8] = std::array::from_fn(|i| pts[corners[i] as usize - 1]);
    (hex_scaled_jacobian(&p) > 0.0).then_some(corners)
}

/// The affine-fit data of the query's vertices (one label per vertex).
fn vertex_fit(map: &CMap3, l: &Labelling) -> Option<AffineFit> {
    let mut seen = rustc_hash::FxHashSet::default();
    let (mut labels, mut points) = (Vec::new(), Vec::new());
    for (k, &d) in l.darts.iter().enumerate() {
        if seen.insert(map.vertex_of(d)) {
            labels.push(k as u32 + 1);
            points.push(map.point(d));
        }
    }
    AffineFit::new(labels, points)
}
