//! Hexahedra → tetrahedra without new points (the synthetic data of 2025 §7.1.1): one
//! diagonal per quadrilateral, shared by the two hexahedra on it (so the result is
//! conformal), then per hexahedron one of the subdivisions of [`HexSplits`] with those
//! diagonals whose tetrahedra are all positive on its own corners.

use std::collections::BTreeMap;

use rustc_hash::FxHashMap;

use super::hex_split::{HEX_FACES, HexSplit, HexSplits};
use crate::build::{CellKind, CellValues, IndexedMesh};

/// Which subdivisions [`tetrahedralize`] draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SplitChoice {
    /// Uniformly among every positive subdivision of each hexahedron (5 to 15 tets).
    Any,
    /// Diagonals from a 2-colouring of the vertices, so that as many hexahedra as
    /// possible take the 5-tetrahedron split (all of them when the hex edges form a
    /// bipartite graph and every 5-tet split is positive).
    Five,
}

/// Options of [`tetrahedralize`].
#[derive(Clone, Copy, Debug)]
pub struct TetrahedralizeOptions {
    pub choice: SplitChoice,
    pub seed: u64,
}

/// What [`tetrahedralize`] did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct TetrahedralizeReport {
    pub hexes: usize,
    pub tets: usize,
    /// Tetrahedra of the input, copied.
    pub tets_kept: usize,
    /// Hexahedra per number of tetrahedra they were split into.
    pub by_tet_count: BTreeMap<usize, usize>,
    /// Hexahedra per subdivision class (index up to the cube's 48 symmetries).
    pub by_class: BTreeMap<usize, usize>,
    /// Whether the hex edges form a bipartite graph (a 5-tet split of every hexahedron
    /// is then combinatorially possible).
    pub bipartite: bool,
    /// Face diagonals flipped to give every hexahedron a positive subdivision.
    pub diagonals_flipped: usize,
}

/// Why a mesh could not be split.
#[derive(Debug, thiserror::Error)]
pub enum TetrahedralizeError {
    #[error("cell {cell} is a {kind}: only hexahedra (split) and tetrahedra (kept) can be tetrahedralized")]
    Unsupported { cell: usize, kind: &'static str },
    #[error(
        "hexahedron {cell} has no subdivision into positive tetrahedra on its corners for any choice of its face diagonals (is it inverted or degenerate?)"
    )]
    NoPositiveSplit { cell: usize },
    #[error("the mesh has no hexahedron")]
    NoHexahedron,
}

/// A quadrilateral by its sorted vertex ids.
fn quad_key(q: [u32; 4]) -> [u32; 4] {
    let mut k = q;
    k.sort_unstable();
    k
}

/// Splits every hexahedron of `mesh` into tetrahedra on its corners (tetrahedra are
/// kept). Output cells carry the arrays `source_cell` (input cell index) and
/// `split_class` (subdivision class, −1 for kept tetrahedra); labels are kept.
///
/// ```
/// use qmesh::apps::{SplitChoice, TetrahedralizeOptions, tetrahedralize};
/// let grid = qmesh::generate::hex_grid(3, 3, 3);
/// let (tets, r) = tetrahedralize(&grid, &TetrahedralizeOptions { choice: SplitChoice::Five, seed: 1 }).unwrap();
/// assert!(r.bipartite);
/// assert_eq!((tets.nb_cells(), r.by_tet_count[&5]), (27 * 5, 27));
/// ```
///
/// # Errors
/// Cells other than hexahedra and tetrahedra, a mesh without hexahedra, or a
/// hexahedron without any positive subdivision (inverted, flat, or too twisted).
pub fn tetrahedralize(
    mesh: &IndexedMesh,
    opts: &TetrahedralizeOptions,
) -> Result<(IndexedMesh, TetrahedralizeReport), TetrahedralizeError> {
    let splits = HexSplits::get();
    let mut hexes: Vec<usize> = Vec::new();
    for c in 0..mesh.nb_cells() {
        match mesh.kinds[c] {
            CellKind::Hex => hexes.push(c),
            CellKind::Tet => {}
            k => return Err(TetrahedralizeError::Unsupported { cell: c, kind: k.name() }),
        }
    }
    if hexes.is_empty() {
        return Err(TetrahedralizeError::NoHexahedron);
    }
    let nodes = |c: usize| -> [u32; 8] { mesh.cell(c).1.try_into().expect("hexahedra have 8 nodes") };
    // Faces: index per quad, and per hexahedron its 6 face indices (HEX_FACES order).
    let mut face_of: FxHashMap<[u32; 4], u32> = FxHashMap::default();
    let mut quads: Vec<[u32; 4]> = Vec::new();
    let hex_faces: Vec<[u32; 6]> = hexes
        .iter()
        .map(|&c| {
            let n = nodes(c);
            HEX_FACES.map(|f| {
                let q = f.map(|i| n[i as usize]);
                *face_of.entry(quad_key(q)).or_insert_with(|| {
                    quads.push(q);
                    quads.len() as u32 - 1
                })
            })
        })
        .collect();
    let mut hexes_of_face: Vec<Vec<u32>> = vec![Vec::new(); quads.len()];
    for (h, faces) in hex_faces.iter().enumerate() {
        faces.iter().for_each(|&f| hexes_of_face[f as usize].push(h as u32));
    }
    let mut rng = crate::random::SplitMix64(opts.seed ^ 0xD1A6_0000);
    let (colour, bipartite) = two_colouring(mesh, &hexes);
    // The chosen diagonal of each quad, as the vertex it starts from (one of q[0], q[1]).
    let mut diagonal: Vec<u32> = quads
        .iter()
        .map(|q| match opts.choice {
            SplitChoice::Five if colour[q[0] as usize] == 0 => q[0],
            SplitChoice::Five if colour[q[1] as usize] == 0 => q[1],
            _ => q[rng.below(2)],
        })
        .collect();
    let candidates = |h: usize, diagonal: &[u32]| -> Vec<&HexSplit> {
        let n = nodes(hexes[h]);
        let mut bits = 0u8;
        for (f, face) in HEX_FACES.iter().enumerate() {
            let d = diagonal[hex_faces[h][f] as usize];
            if d == n[face[1] as usize] || d == n[face[3] as usize] {
                bits |= 1 << f;
            }
        }
        splits.with_diagonals(bits).filter(|s| s.is_positive_on(&n, &mesh.points)).collect()
    };
    // Repair: hexahedra without a positive subdivision flip one of their diagonals
    // (re-checking the neighbour), a bounded number of times.
    let mut report = TetrahedralizeReport { hexes: hexes.len(), bipartite, ..Default::default() };
    let mut failing: Vec<usize> = (0..hexes.len()).filter(|&h| candidates(h, &diagonal).is_empty()).collect();
    let mut rounds = 0;
    while let Some(&h) = failing.last() {
        if !candidates(h, &diagonal).is_empty() {
            failing.pop();
            continue;
        }
        rounds += 1;
        if rounds > 64 * hexes.len() + 1000 {
            return Err(TetrahedralizeError::NoPositiveSplit { cell: hexes[h] });
        }
        let f = hex_faces[h][rng.below(6)] as usize;
        let q = quads[f];
        diagonal[f] = if diagonal[f] == q[0] { q[1] } else { q[0] };
        report.diagonals_flipped += 1;
        // The hexahedra on that face may have lost their split.
        for &g in &hexes_of_face[f] {
            if g as usize != h && candidates(g as usize, &diagonal).is_empty() {
                failing.push(g as usize);
            }
        }
    }
    let mut out = IndexedMesh { points: mesh.points.clone(), ..IndexedMesh::new() };
    let labelled = !mesh.labels.is_empty();
    let (mut source, mut class) = (Vec::new(), Vec::new());
    let mut h = 0;
    for c in 0..mesh.nb_cells() {
        let label = labelled.then(|| mesh.labels[c]);
        if mesh.kinds[c] == CellKind::Tet {
            out.push_cell(CellKind::Tet, mesh.cell(c).1, label);
            source.push(c as i32);
            class.push(-1);
            report.tets_kept += 1;
            continue;
        }
        let cands = candidates(h, &diagonal);
        let chosen = match opts.choice {
            SplitChoice::Five => *cands.iter().min_by_key(|s| s.tets.len()).expect("repaired"),
            SplitChoice::Any => cands[rng.below(cands.len())],
        };
        let n = nodes(c);
        for t in &chosen.tets {
            out.push_cell(CellKind::Tet, &t.map(|i| n[i as usize]), label);
            source.push(c as i32);
            class.push(chosen.class as i32);
        }
        *report.by_tet_count.entry(chosen.tets.len()).or_insert(0) += 1;
        *report.by_class.entry(chosen.class).or_insert(0) += 1;
        h += 1;
    }
    report.tets = out.nb_cells();
    out.set_cell_array("source_cell", CellValues::Int(source));
    out.set_cell_array("split_class", CellValues::Int(class));
    Ok((out, report))
}

/// A 2-colouring of the vertices along hex edges (breadth-first; a vertex whose
/// neighbours disagree keeps its first colour) and whether it is proper.
fn two_colouring(mesh: &IndexedMesh, hexes: &[usize]) -> (Vec<u8>, bool) {
    const EDGES: [[usize; 2]; 12] =
        [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4], [0, 4], [1, 5], [2, 6], [3, 7]];
    let np = mesh.points.len();
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); np];
    for &c in hexes {
        let n = mesh.cell(c).1;
        for [a, b] in EDGES {
            adj[n[a] as usize].push(n[b]);
            adj[n[b] as usize].push(n[a]);
        }
    }
    let mut colour = vec![u8::MAX; np];
    let mut proper = true;
    for s in 0..np {
        if colour[s] != u8::MAX || adj[s].is_empty() {
            continue;
        }
        colour[s] = 0;
        let mut queue = std::collections::VecDeque::from([s]);
        while let Some(v) = queue.pop_front() {
            for &w in &adj[v] {
                let w = w as usize;
                if colour[w] == u8::MAX {
                    colour[w] = colour[v] ^ 1;
                    queue.push_back(w);
                } else if colour[w] == colour[v] {
                    proper = false;
                }
            }
        }
    }
    (colour, proper)
}
