//! Indexed volume cells → 3-map: one volume per cell, shared faces 3-sewn.

use super::adjacency::{VertexCells, check_cells};
use super::error::BuildError;
use super::indexed::{CellKind, IndexedMesh};
use crate::cmap::{CMap3, Dart, Orbit};
use crate::geom::{signed_volume_of_faces, signed_volume_of_table};

/// Options of [`build_volume_map`].
#[derive(Clone, Copy, Debug, Default)]
pub struct BuildOptions {
    /// Flip cells whose signed volume is negative instead of only counting them.
    pub fix_orientation: bool,
}

/// What the builder saw and did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildReport {
    /// Cells with negative signed volume in the input node order.
    pub inverted_cells: usize,
    /// Of those, how many were flipped (`fix_orientation`).
    pub flipped_cells: usize,
    /// Cells with zero volume.
    pub degenerate_cells: usize,
    /// Vertices touched by cells that share no face there (non-manifold), which the map
    /// represents as several vertices.
    pub split_vertices: usize,
    /// Points that no cell uses.
    pub unreferenced_points: usize,
}

/// Where the darts of each cell are: standard cells are created in one contiguous block
/// (the map is fresh), so their faces are found from the kind's layout; polyhedra keep
/// the first dart of each face.
struct CellDarts {
    /// First dart of each cell.
    first: Vec<u32>,
    /// Polyhedra: cell → first darts of its faces.
    poly_faces: rustc_hash::FxHashMap<u32, Vec<u32>>,
}

/// How a face of another cell relates to a face.
enum FaceMatch {
    /// Same vertex cycle, opposite direction: the dart to 3-sew with.
    Opposite(Dart),
    /// Same vertex cycle, same direction.
    Same,
    None,
}

fn dart(raw: u32) -> Dart {
    Dart::from_raw(raw).expect("cell index holds live darts")
}

/// Whether the faces of `d` and `y` have the same vertex cycle in opposite directions,
/// with y running target(d) → origin(d).
fn opposite_cycles(map: &CMap3, d: Dart, y: Dart) -> bool {
    let (mut a, mut b) = (d, y);
    loop {
        if map.vertex_of(map.next(a)) != map.vertex_of(b) || map.vertex_of(a) != map.vertex_of(map.next(b)) {
            return false;
        }
        a = map.next(a);
        b = map.prev(b);
        if a == d || b == y {
            return a == d && b == y;
        }
    }
}

/// Whether the faces of `d` and `z` have the same vertex cycle in the same direction,
/// with z starting where d starts.
fn same_cycles(map: &CMap3, d: Dart, z: Dart) -> bool {
    let (mut a, mut b) = (d, z);
    loop {
        if map.vertex_of(a) != map.vertex_of(b) {
            return false;
        }
        a = map.next(a);
        b = map.next(b);
        if a == d || b == z {
            return a == d && b == z;
        }
    }
}

/// Compares the face of `d` with the face of `e` by their vertex cycles (any faces).
fn compare_faces(map: &CMap3, d: Dart, e: Dart) -> FaceMatch {
    let (origin, target) = (map.vertex_of(d), map.vertex_of(map.next(d)));
    let mut x = e;
    loop {
        if map.vertex_of(x) == target && map.vertex_of(map.next(x)) == origin && opposite_cycles(map, d, x) {
            return FaceMatch::Opposite(x);
        }
        if map.vertex_of(x) == origin && map.vertex_of(map.next(x)) == target && same_cycles(map, d, x) {
            return FaceMatch::Same;
        }
        x = map.next(x);
        if x == e {
            return FaceMatch::None;
        }
    }
}

impl CellDarts {
    /// First darts of the faces of cell `c`.
    fn faces(&self, kinds: &[CellKind], c: u32) -> Vec<u32> {
        match kinds[c as usize].standard() {
            Some(k) => {
                let l = k.layout();
                l.face_start[..l.face_start.len() - 1].iter().map(|&s| self.first[c as usize] + s as u32).collect()
            }
            None => self.poly_faces[&c].clone(),
        }
    }

    /// The distinct vertex ids of cell `c`, read from its darts.
    fn nodes(&self, map: &CMap3, kinds: &[CellKind], c: usize, out: &mut Vec<u32>) {
        out.clear();
        match kinds[c].standard() {
            Some(k) => {
                let l = k.layout();
                let first = self.first[c];
                out.extend((0..k.nodes()).map(|n| map.vertex_of(dart(first + l.dart_of_node(n) as u32))));
            }
            None => {
                for &f in &self.poly_faces[&(c as u32)] {
                    out.extend(map.orbit(dart(f), Orbit::HalfFace).iter().map(|&x| map.vertex_of(x)));
                }
                out.sort_unstable();
                out.dedup();
            }
        }
    }

    /// How the face of `d` (running a → b) relates to the faces of cell `c2`.
    fn match_in(&self, map: &CMap3, kinds: &[CellKind], c2: u32, d: Dart) -> FaceMatch {
        let (a, b) = (map.vertex_of(d), map.vertex_of(map.next(d)));
        let Some(kind) = kinds[c2 as usize].standard() else {
            return self.poly_faces[&c2]
                .iter()
                .map(|&g| compare_faces(map, d, dart(g)))
                .find(|m| !matches!(m, FaceMatch::None))
                .unwrap_or(FaceMatch::None);
        };
        let first = self.first[c2 as usize];
        let n = kind.layout().origin.len() as u32;
        for x in (first..first + n).map(dart) {
            let (from, to) = (map.vertex_of(x), map.vertex_of(map.next(x)));
            if (from, to) == (b, a) && opposite_cycles(map, d, x) {
                return FaceMatch::Opposite(x);
            }
            if (from, to) == (a, b) && same_cycles(map, d, x) {
                return FaceMatch::Same;
            }
        }
        FaceMatch::None
    }
}

/// Builds a volume map from the cells of `mesh`.
///
/// # Errors
/// A node index out of range, a degenerate cell (repeated node), a polyhedron that is
/// not closed and manifold, a face shared by more than two cells, or two cells meeting
/// with inconsistent orientation.
pub fn build_volume_map(mesh: &IndexedMesh, opts: &BuildOptions) -> Result<(CMap3, BuildReport), BuildError> {
    let (map, cells, report) = create_cells(mesh, mesh.points.clone(), opts)?;
    sew_and_finish(map, cells, &mesh.kinds, report)
}

/// As [`build_volume_map`], taking the mesh by value: its points move into the map and
/// its connectivity is freed once the darts exist (lower peak memory when loading).
pub fn build_volume_map_owned(mut mesh: IndexedMesh, opts: &BuildOptions) -> Result<(CMap3, BuildReport), BuildError> {
    let points = std::mem::take(&mut mesh.points);
    let (map, cells, report) = create_cells(&mesh, points, opts)?;
    let kinds = std::mem::take(&mut mesh.kinds);
    drop(mesh);
    sew_and_finish(map, cells, &kinds, report)
}

/// Creates one volume per cell of `mesh` (whose own points are not read: the map gets
/// `points`), oriented and labelled; nothing is sewn yet.
fn create_cells(
    mesh: &IndexedMesh,
    points: Vec<[f64; 3]>,
    opts: &BuildOptions,
) -> Result<(CMap3, CellDarts, BuildReport), BuildError> {
    if mesh.nb_cells() == 0 {
        return Err(BuildError::Empty);
    }
    check_cells(mesh, points.len())?;
    let mut report = BuildReport::default();
    let darts: usize = (0..mesh.nb_cells())
        .map(|c| match mesh.kinds[c].standard() {
            Some(k) => k.layout().origin.len(),
            None => mesh.offsets[c + 1] - mesh.offsets[c],
        })
        .sum();
    let mut map = CMap3::with_positions(points, darts);
    let labelled = mesh.labels.iter().any(|&l| l != mesh.labels[0]);
    if labelled {
        map.enable_labels();
    } else if let Some(&l) = mesh.labels.first() {
        map.set_uniform_label(l);
    }
    let mut cells = CellDarts { first: Vec::with_capacity(mesh.nb_cells()), poly_faces: Default::default() };
    let signs = standard_cell_signs(mesh, map.positions());
    let mut out = [0u32; 24];
    for (c, &sign) in signs.iter().enumerate() {
        let (kind, nodes) = mesh.cell(c);
        let label = if labelled { mesh.labels[c] } else { 0 };
        if let Some(std) = kind.standard() {
            let mut n = [0u32; 8];
            n[..nodes.len()].copy_from_slice(nodes);
            if sign < 0 {
                report.inverted_cells += 1;
                if opts.fix_orientation {
                    for (k, &from) in kind.flipped_order().iter().enumerate() {
                        n[k] = nodes[from];
                    }
                    report.flipped_cells += 1;
                }
            } else if sign == 0 {
                report.degenerate_cells += 1;
            }
            let count = map.make_standard_cell(std, &n, &mut out);
            debug_assert!((0..count).all(|k| out[k] == out[0] + k as u32), "a fresh map allocates contiguously");
            cells.first.push(out[0]);
            if labelled {
                out[..count].iter().for_each(|&d| map.set_label_of(dart(d), label));
            }
        } else {
            let mut fs = mesh
                .cell_faces(c)
                .ok_or_else(|| BuildError::BadCell { cell: c, reason: "malformed polyhedron face stream".into() })?;
            let vol = signed_volume_of_faces(&fs, map.positions());
            if vol < 0.0 {
                report.inverted_cells += 1;
                if opts.fix_orientation {
                    fs.iter_mut().for_each(|f| f.reverse());
                    report.flipped_cells += 1;
                }
            } else if vol == 0.0 {
                report.degenerate_cells += 1;
            }
            let firsts =
                map.make_polyhedron_faces(&fs).map_err(|e| BuildError::BadCell { cell: c, reason: e.to_string() })?;
            cells.first.push(firsts[0].raw());
            cells.poly_faces.insert(c as u32, firsts.iter().map(|d| d.raw()).collect());
            if labelled {
                for d in map.orbit(firsts[0], Orbit::Volume) {
                    map.set_label_of(d, label);
                }
            }
        }
    }
    Ok((map, cells, report))
}

/// The sign of the signed volume of every standard cell in its input node order (0
/// for polyhedra, which are measured as they are built), computed in parallel.
fn standard_cell_signs(mesh: &IndexedMesh, points: &[[f64; 3]]) -> Vec<i8> {
    use rayon::prelude::*;
    (0..mesh.nb_cells())
        .into_par_iter()
        .with_min_len(1 << 10)
        .map(|c| {
            let (kind, nodes) = mesh.cell(c);
            let vol = kind.standard().map_or(0.0, |k| signed_volume_of_table(k.faces(), nodes, points));
            if vol < 0.0 { -1 } else { i8::from(vol > 0.0) }
        })
        .collect()
}

/// Sews the cells' shared faces (found through a vertex → cells incidence read from
/// the darts), counts unused points and splits non-manifold vertices.
fn sew_and_finish(
    mut map: CMap3,
    cells: CellDarts,
    kinds: &[CellKind],
    mut report: BuildReport,
) -> Result<(CMap3, BuildReport), BuildError> {
    let np = map.nb_vertex_ids();
    let adj = VertexCells::new(np, kinds.len(), |c, out| cells.nodes(&map, kinds, c, out));
    sew_shared_faces(&mut map, kinds, &cells, &adj)?;
    report.unreferenced_points = (0..np as u32).filter(|&v| adj.is_unused(v)).count();
    drop((adj, cells));
    report.split_vertices = split_shared_vertex_ids(&mut map);
    Ok((map, report))
}

/// 3-sews every face to the face of a neighbouring cell with the opposite cycle.
fn sew_shared_faces(
    map: &mut CMap3,
    kinds: &[CellKind],
    cells: &CellDarts,
    adj: &VertexCells,
) -> Result<(), BuildError> {
    for c in 0..kinds.len() as u32 {
        'face: for f in cells.faces(kinds, c) {
            let d = dart(f);
            if !map.is_free(d, 3) {
                continue;
            }
            let (a, b) = (map.vertex_of(d), map.vertex_of(map.next(d)));
            let third = map.vertex_of(map.next(map.next(d)));
            for c2 in adj.common3(a, b, third).filter(|&c2| c2 != c) {
                match cells.match_in(map, kinds, c2, d) {
                    FaceMatch::None => {}
                    FaceMatch::Same => {
                        // A third cell on the face is the real defect (orientation
                        // cannot fix it): name the three.
                        let mut cells3 = adj.common3(a, b, third).filter(|&x| {
                            x != c && x != c2 && !matches!(cells.match_in(map, kinds, x, d), FaceMatch::None)
                        });
                        if let Some(c3) = cells3.next() {
                            let mut three = [c as usize, c2 as usize, c3 as usize];
                            three.sort_unstable();
                            return Err(BuildError::FaceSharedByMoreThanTwo {
                                face: cycle(map, d),
                                a: three[0],
                                b: three[1],
                                c: three[2],
                            });
                        }
                        return Err(BuildError::InconsistentOrientation {
                            face: cycle(map, d),
                            a: c2.min(c) as usize,
                            b: c2.max(c) as usize,
                        });
                    }
                    FaceMatch::Opposite(y) => {
                        if let Some(taken) = map.beta(y, 3) {
                            let third = owner(map, kinds, cells, adj, (a, b), taken, [c, c2]);
                            return Err(BuildError::FaceSharedByMoreThanTwo {
                                face: cycle(map, d),
                                a: c2 as usize,
                                b: third,
                                c: c as usize,
                            });
                        }
                        map.link_faces3(d, y);
                        continue 'face;
                    }
                }
            }
        }
    }
    Ok(())
}

fn cycle(map: &CMap3, d: Dart) -> Vec<u32> {
    map.orbit(d, Orbit::HalfFace).iter().map(|&x| map.vertex_of(x)).collect()
}

/// The cell (other than the two named) whose face holds dart `taken` (error reporting).
fn owner(
    map: &CMap3,
    kinds: &[CellKind],
    cells: &CellDarts,
    adj: &VertexCells,
    (a, b): (u32, u32),
    taken: Dart,
    not: [u32; 2],
) -> usize {
    let volume = map.orbit(taken, Orbit::Volume);
    adj.common(a, b)
        .filter(|k| !not.contains(k))
        .find(|&k| cells.faces(kinds, k).iter().any(|&f| volume.contains(&dart(f))))
        .map_or(usize::MAX, |k| k as usize)
}

/// Gives a fresh vertex id to every vertex orbit whose id another orbit already uses
/// (cells touching only at a vertex or an edge); returns how many were split. The
/// parallel check settles the common case (no such vertex) without the sequential walk.
fn split_shared_vertex_ids(map: &mut CMap3) -> usize {
    if !map.has_shared_vertex_id() {
        return 0;
    }
    let reps: Vec<Dart> = map.cells(Orbit::Vertex).collect();
    let mut seen = vec![false; map.nb_vertex_ids()];
    let mut split = 0;
    for d in reps {
        let v = map.vertex_of(d) as usize;
        if !seen[v] {
            seen[v] = true;
            continue;
        }
        let fresh = map.add_vertex(map.position(v as u32));
        for x in map.orbit(d, Orbit::Vertex) {
            map.set_vertex_of(x, fresh);
        }
        split += 1;
    }
    split
}
