//! Marching cubes of a field by compiled query-replace. Every cell of a grid is the same
//! cube, so what query-replace makes of a cell depends only on which corners are inside
//! and on which of its faces it shares with a lower neighbour (a shared face is matched
//! from the half-face of the cell that comes first, 2022 §5.1.1). Each such case met in
//! the field is query-replaced once, by [`march`], on a map of the cell and those
//! neighbours; the surface polygons it gives, as cube edges, are then laid on every cell
//! of that case. The surface is the one the map of all crossed cells gives, polygon for
//! polygon (tested against [`super::mc_field`]'s slabs), at the cost of a table lookup
//! per cell. Sets whose patterns place vertices inside cubes, or leave a case unmatched,
//! are marched on maps instead.

use rayon::prelude::*;

use super::marching_cubes::{McFlags, McReport, march};
use super::mc_grid::{CORNERS, Grid};
use crate::build::{BuildOptions, CellKind, IndexedMesh, build_map};
use crate::pattern::{PatternKind, PatternSet};

/// A case's surface: polygons whose vertices are cube edges, as (inside corner, outside
/// corner) in [`CORNERS`] order.
type Case = Vec<Vec<[u8; 2]>>;

/// The lower faces (i−, j−, k−) as corner sets, with the neighbour's offset.
const LOWER_FACES: [([usize; 4], [usize; 3]); 3] =
    [([0, 3, 4, 7], [0, 1, 1]), ([0, 1, 4, 5], [1, 0, 1]), ([0, 1, 2, 3], [1, 1, 0])];

/// The six faces as corner sets.
const FACES: [[usize; 4]; 6] = [[0, 3, 4, 7], [1, 2, 5, 6], [0, 1, 4, 5], [2, 3, 6, 7], [0, 1, 2, 3], [4, 5, 6, 7]];

fn face_crossed(configuration: u8, face: &[usize; 4]) -> bool {
    let side = |c: usize| configuration >> c & 1;
    face.iter().any(|&c| side(c) != side(face[0]))
}

/// A cell's case: its configuration, and bit 8 + a for each lower face (axis a) that a
/// neighbour shares and that the surface crosses (only those faces are replaced).
fn case_key(configuration: u8, cell: [usize; 3]) -> usize {
    LOWER_FACES.iter().enumerate().fold(usize::from(configuration), |key, (axis, (face, _))| {
        key | (usize::from(cell[axis] > 0 && face_crossed(configuration, face)) << (8 + axis))
    })
}

/// Query-replaces the cases `keys`, each on a unit cube and its lower neighbours, all in
/// one map (case n at x = 4n + 1, apart from the others: one march for all, each cell's
/// darts in the order the whole grid gives them); None when a vertex of a surface is not
/// on an edge or a cell is unmatched.
fn compile(keys: &[usize], set: &PatternSet, flags: McFlags) -> Option<Vec<Case>> {
    const SPACING: usize = 4;
    let mut cells = IndexedMesh::new();
    for n in 0..keys.len() {
        cells.points.extend((0..27).map(|p| [SPACING * n + p / 9, p / 3 % 3, p % 3].map(|x| x as f64)));
    }
    for (n, &key) in keys.iter().enumerate() {
        let point = |o: [usize; 3]| (27 * n + 9 * o[0] + 3 * o[1] + o[2]) as u32;
        // In the order of the whole grid's cells (k, then j, then i): the neighbours first.
        for axis in [2, 1, 0] {
            if key >> (8 + axis) & 1 == 1 {
                let at = LOWER_FACES[axis].1;
                cells.push_cell(CellKind::Hex, &CORNERS.map(|c| point([0, 1, 2].map(|x| at[x] + c[x]))), None);
            }
        }
        cells.push_cell(CellKind::Hex, &CORNERS.map(|c| point(c.map(|x| x + 1))), None);
    }
    let (mut map, _) = build_map(cells, &BuildOptions::default()).ok()?;
    // The case and main-cube corner of each vertex (no corner for a neighbour's own).
    let place: Vec<(usize, Option<u8>)> = (0..map.nb_vertex_ids() as u32)
        .map(|v| {
            let p = map.position(v).map(|x| x as usize);
            let (n, local) = (p[0] / SPACING, [p[0] % SPACING, p[1], p[2]]);
            (n, CORNERS.iter().position(|c| (0..3).all(|x| c[x] + 1 == local[x])).map(|c| c as u8))
        })
        .collect();
    let inside: Vec<bool> = place.iter().map(|&(n, c)| c.is_some_and(|c| keys[n] >> c & 1 == 1)).collect();
    let owns = |vertices: &mut dyn Iterator<Item = u32>| {
        for v in vertices {
            if place[v as usize].1.is_none() {
                return false;
            }
        }
        true
    };
    let m = march(&mut map, &inside, &|_, _| [0.5; 3], set, flags, Some(&owns)).ok()?;
    if m.report.unmatched_volumes + m.report.unmatched_faces > 0 {
        return None;
    }
    let edge = |e: Option<[u32; 2]>| {
        let [a, b] = e?;
        Some((place[a as usize].0, [place[a as usize].1?, place[b as usize].1?]))
    };
    let edges: Vec<(usize, [u8; 2])> = m.edge_ends.iter().map(|&e| edge(e)).collect::<Option<_>>()?;
    let mut cases: Vec<Case> = vec![Vec::new(); keys.len()];
    for i in 0..m.surface.nb_polygons() {
        let poly = m.surface.polygon(i);
        let n = edges[poly[0] as usize].0;
        cases[n].push(poly.iter().map(|&v| edges[v as usize].1).collect());
    }
    Some(cases)
}

/// Marching cubes of `grid` by compiled cases (see the module); None when a case does
/// not compile (the caller marches maps then).
pub(super) fn march_compiled(
    grid: &Grid,
    layers: &[Vec<(u32, u8)>],
    set: &PatternSet,
    flags: McFlags,
) -> Option<(IndexedMesh, McReport)> {
    let t = std::time::Instant::now();
    let [nx, _, nz] = grid.dims;
    let cell_of = |k: usize, c: u32| [c as usize % (nx - 1), c as usize / (nx - 1), k];
    // The cases met, compiled once each.
    let needed = layers
        .par_iter()
        .enumerate()
        .fold(
            || vec![false; 1 << 11],
            |mut seen, (k, layer)| {
                for &(c, configuration) in layer {
                    seen[case_key(configuration, cell_of(k, c))] = true;
                }
                seen
            },
        )
        .reduce(|| vec![false; 1 << 11], |a, b| a.iter().zip(&b).map(|(x, y)| x | y).collect());
    let keys: Vec<usize> = (0..needed.len()).filter(|&k| needed[k]).collect();
    // (64 cases per map: the maps are marched on all cores)
    let compiled: Vec<Vec<Case>> = keys.par_chunks(64).map(|k| compile(k, set, flags)).collect::<Option<_>>()?;
    let compiled = compiled.concat();
    let mut cases: Vec<Option<&Case>> = vec![None; 1 << 11];
    for (&k, c) in keys.iter().zip(&compiled) {
        cases[k] = Some(c);
    }
    let compile_seconds = t.elapsed().as_secs_f64();
    let t = std::time::Instant::now();
    let (edges, points) = EdgeIds::new(grid);
    let points_seconds = t.elapsed().as_secs_f64();
    let t = std::time::Instant::now();
    // Each run of layers lays its cells' polygons with the edges' global ids.
    let chunk = 8;
    let laid: Vec<(Vec<u32>, Vec<u32>, usize)> = (0..nz - 1)
        .step_by(chunk)
        .collect::<Vec<_>>()
        .par_iter()
        .map(|&k0| {
            let (mut sizes, mut conn, mut faces) = (Vec::new(), Vec::new(), 0);
            let mut window = EdgeWindow::default();
            for (k, layer) in layers.iter().enumerate().skip(k0).take(chunk) {
                window.move_to(grid, &edges, k);
                for &(c, configuration) in layer {
                    let cell = cell_of(k, c);
                    let key = case_key(configuration, cell);
                    for poly in cases[key].expect("every case met was compiled") {
                        sizes.push(poly.len() as u32);
                        conn.extend(poly.iter().map(|&[a, b]| window.id(grid, cell, a, b)));
                    }
                    // A crossed face shared with a lower cell was counted by that cell.
                    faces += FACES.iter().filter(|f| face_crossed(configuration, f)).count();
                    faces -= (0..3).filter(|&axis| key >> (8 + axis) & 1 == 1).count();
                }
            }
            (sizes, conn, faces)
        })
        .collect();
    let mut surface = IndexedMesh::new();
    surface.points = points;
    let mut r = McReport {
        f_patterns: set.count(PatternKind::Face),
        v_patterns: set.count(PatternKind::Volume),
        edges_split: surface.points.len(),
        ..Default::default()
    };
    surface.poly_offsets.reserve(laid.iter().map(|l| l.0.len()).sum());
    for (sizes, conn, faces) in laid {
        let mut end = surface.poly_conn.len();
        for n in sizes {
            end += n as usize;
            surface.poly_offsets.push(end);
        }
        surface.poly_conn.extend(conn);
        r.faces_replaced += faces;
    }
    r.cells_built = layers.iter().map(Vec::len).sum();
    r.volumes_replaced = r.cells_built;
    r.polygons = surface.nb_polygons();
    r.phases.compile = compile_seconds;
    r.phases.points = points_seconds;
    r.phases.lay = t.elapsed().as_secs_f64();
    Some((surface, r))
}

/// The global id of every crossing edge: the edges of plane k = 0 (by point, j then i;
/// along i, then j), then those from plane 0 to plane 1 (along k), then plane 1's, and
/// so on; `first[g]` is the first id of group g (2k: plane k, 2k + 1: between k and
/// k + 1) and `slots[g]` the table slot of each of its edges (see [`EdgeWindow`]).
struct EdgeIds {
    first: Vec<u32>,
    slots: Vec<Vec<u32>>,
}

impl EdgeIds {
    /// The ids and the crossing points in id order.
    fn new(grid: &Grid) -> (Self, Vec<[f64; 3]>) {
        let [nx, ny, nz] = grid.dims;
        let slots: Vec<Vec<u32>> = (0..2 * nz - 1)
            .into_par_iter()
            .map(|g| {
                let mut slots = Vec::new();
                group_edges(grid, g, |_, _, slot| slots.push(slot));
                slots
            })
            .collect();
        let mut first = Vec::with_capacity(slots.len() + 1);
        let mut at = 0;
        for s in &slots {
            first.push(at);
            at += s.len() as u32;
        }
        first.push(at);
        // The points, each group's slice filled on its own core.
        let mut points = vec![[0.0; 3]; at as usize];
        let mut rest = points.as_mut_slice();
        let mut parts = Vec::with_capacity(slots.len());
        for (g, s) in slots.iter().enumerate() {
            let (part, tail) = rest.split_at_mut(s.len());
            parts.push((g, part));
            rest = tail;
        }
        let step = [ny * nz, nz, 1];
        parts.into_par_iter().for_each(|(g, part)| {
            for (p, &slot) in part.iter_mut().zip(&slots[g]) {
                let (cell, axis) = (slot as usize / 3, slot as usize % 3);
                let a = grid.index([cell % nx, cell / nx, g / 2]);
                let b = a + step[axis];
                *p = if grid.is_inside(a) { grid.crossing(a, b) } else { grid.crossing(b, a) };
            }
        });
        (EdgeIds { first, slots }, points)
    }
}

/// Calls `f(a, b, slot)` for each crossing edge of group g (see [`EdgeIds`]) in id
/// order: its grid points and its slot (j·nx + i)·3 + axis in the group's table.
fn group_edges(grid: &Grid, g: usize, mut f: impl FnMut(usize, usize, u32)) {
    let [nx, ny, nz] = grid.dims;
    let k = g / 2;
    for j in 0..ny {
        for i in 0..nx {
            let a = grid.index([i, j, k]);
            let slot = ((j * nx + i) * 3) as u32;
            let mut edge = |b: usize, axis: u32| {
                if grid.is_inside(a) != grid.is_inside(b) {
                    f(a, b, slot + axis);
                }
            };
            if g % 2 == 1 {
                edge(a + 1, 2);
            } else {
                if i + 1 < nx {
                    edge(a + ny * nz, 0);
                }
                if j + 1 < ny {
                    edge(a + nz, 1);
                }
            }
        }
    }
}

/// The ids of the crossing edges of the cells of one layer k: groups 2k, 2k + 1 and
/// 2k + 2, each as a table by (point, axis) filled when the layer is reached.
#[derive(Default)]
struct EdgeWindow {
    layer: Option<usize>,
    /// Per group of the window, the id of each (j·nx + i)·3 + axis.
    ids: [Vec<u32>; 3],
}

impl EdgeWindow {
    fn move_to(&mut self, grid: &Grid, edges: &EdgeIds, k: usize) {
        let [nx, ny, _] = grid.dims;
        if self.layer == Some(k) {
            return;
        }
        let shift = self.layer == Some(k.wrapping_sub(1));
        self.layer = Some(k);
        if shift {
            self.ids.swap(0, 2);
        }
        for w in if shift { 1..3 } else { 0..3 } {
            let g = 2 * k + w;
            // (never cleared: a cell only asks for crossing edges, which its group sets)
            let table = &mut self.ids[w];
            table.resize(3 * nx * ny, u32::MAX);
            if let Some(slots) = edges.slots.get(g) {
                for (n, &slot) in slots.iter().enumerate() {
                    table[slot as usize] = edges.first[g] + n as u32;
                }
            }
        }
    }

    /// The id of the edge between corners a and b of `cell` (in layer k).
    fn id(&self, grid: &Grid, cell: [usize; 3], a: u8, b: u8) -> u32 {
        let (ca, cb) = (CORNERS[a as usize], CORNERS[b as usize]);
        let low = [0, 1, 2].map(|x| cell[x] + ca[x].min(cb[x]));
        let axis = (0..3).find(|&x| ca[x] != cb[x]).expect("an edge joins two corners");
        let k = self.layer.expect("the window is on a layer");
        // Plane k (w = 0), between k and k + 1 (w = 1), plane k + 1 (w = 2).
        let w = if axis == 2 { 1 } else { 2 * (low[2] - k) };
        self.ids[w][(low[1] * grid.dims[0] + low[0]) * 3 + axis]
    }
}
