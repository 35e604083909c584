//! Conformity (2022 §7.3): a mesh is conformal when two cells meet in a whole shared
//! face, edge or vertex, i.e. no vertex lies on a face, or an edge, it is not a vertex
//! of ("hanging" vertices, T-junctions).

use rayon::prelude::*;
use smallvec::SmallVec;

use crate::cmap::{CMap3, Dart};
use crate::geom::{Aabb, cross, dot, sub};

/// Vertex ids bucketed on a uniform grid: (cell key, vertex id) sorted by key.
struct Grid {
    lo: [f64; 3],
    cell: f64,
    entries: Vec<([i64; 3], u32)>,
}

impl Grid {
    fn key(&self, p: [f64; 3]) -> [i64; 3] {
        [0, 1, 2].map(|k| ((p[k] - self.lo[k]) / self.cell).floor() as i64)
    }

    /// The vertex ids in the grid cell `key`.
    fn bucket(&self, key: [i64; 3]) -> impl Iterator<Item = u32> + '_ {
        let start = self.entries.partition_point(|e| e.0 < key);
        self.entries[start..].iter().take_while(move |e| e.0 == key).map(|e| e.1)
    }
}

/// Number of faces not shared by two cells (3-free) that some vertex touches at a
/// position other than their corners, inside the face or on one of its edges: 0 for a
/// conformal mesh; each coarse face next to finer cells counts in a hanging-node mesh.
/// Only 3-free faces are examined: cells meeting in part of a face, or at a vertex in
/// the middle of an edge, always leave unshared faces inside the mesh.
pub fn non_conformal_faces(map: &CMap3) -> usize {
    let faces: Vec<Dart> = map.darts().filter(|&d| map.is_free(d, 3) && is_smallest_of_face(map, d)).collect();
    non_conformal_faces_of(map, &faces)
}

/// As [`non_conformal_faces`], given one dart of every unshared face (as
/// [`Census::boundary_reps`](crate::cmap::Census) lists them).
pub fn non_conformal_faces_of(map: &CMap3, faces: &[Dart]) -> usize {
    if faces.is_empty() {
        return 0;
    }
    // A vertex touching an unshared face lies on unshared faces itself (those of the
    // finer cells on the other side), so only their vertices are bucketed.
    let mut ids: Vec<u32> = faces.iter().flat_map(|&d| face_vertices(map, d)).collect();
    ids.sort_unstable();
    ids.dedup();
    let b = Aabb::of(ids.iter().map(|&v| map.position(v)));
    // Buckets about the size of a face (the mean length of the first edges).
    let mean_edge = faces
        .iter()
        .map(|&d| dot(sub(map.point(map.next(d)), map.point(d)), sub(map.point(map.next(d)), map.point(d))).sqrt())
        .sum::<f64>()
        / faces.len().max(1) as f64;
    let cell = mean_edge.max(f64::MIN_POSITIVE);
    let mut grid = Grid { lo: b.lo, cell, entries: Vec::with_capacity(ids.len()) };
    grid.entries = ids.iter().map(|&v| (grid.key(map.position(v)), v)).collect();
    grid.entries.par_sort_unstable();
    faces.par_iter().filter(|&&d| face_is_touched(map, &grid, d)).count()
}

fn is_smallest_of_face(map: &CMap3, d: Dart) -> bool {
    let mut x = map.next(d);
    while x != d {
        if x < d {
            return false;
        }
        x = map.next(x);
    }
    true
}

/// The vertex ids around the half-face of `d`, in cycle order (inline up to 8).
fn face_vertices(map: &CMap3, d: Dart) -> SmallVec<[u32; 8]> {
    let mut verts = SmallVec::new();
    let mut x = d;
    loop {
        verts.push(map.vertex_of(x));
        x = map.next(x);
        if x == d {
            return verts;
        }
    }
}

fn face_is_touched(map: &CMap3, grid: &Grid, d: Dart) -> bool {
    let verts = face_vertices(map, d);
    let pts: SmallVec<[[f64; 3]; 8]> = verts.iter().map(|&v| map.position(v)).collect();
    let fb = Aabb::of(pts.iter().copied());
    let fe = fb.extent();
    let tol = 1e-7 * dot(fe, fe).sqrt();
    let (klo, khi) = (grid.key(fb.lo.map(|c| c - tol)), grid.key(fb.hi.map(|c| c + tol)));
    for i in klo[0]..=khi[0] {
        for j in klo[1]..=khi[1] {
            for k in klo[2]..=khi[2] {
                for w in grid.bucket([i, j, k]) {
                    let q = map.position(w);
                    let own = verts.contains(&w) || pts.iter().any(|&p| dot(sub(p, q), sub(p, q)).sqrt() <= tol);
                    if !own && on_polygon(&pts, q, tol) {
                        return true;
                    }
                }
            }
        }
    }
    false
}

/// Whether `q` lies on the (planar) polygon `p`, boundary included, within `tol`.
fn on_polygon(p: &[[f64; 3]], q: [f64; 3], tol: f64) -> bool {
    let n = p.iter().zip(p.iter().cycle().skip(1)).fold([0.0; 3], |n, (a, b)| {
        let c = cross(*a, *b);
        [n[0] + c[0], n[1] + c[1], n[2] + c[2]]
    });
    let ln = dot(n, n).sqrt();
    if ln == 0.0 || (dot(n, sub(q, p[0])) / ln).abs() > tol {
        return false;
    }
    // On an edge?
    for (a, b) in p.iter().zip(p.iter().cycle().skip(1)) {
        let (ab, aq) = (sub(*b, *a), sub(q, *a));
        let t = (dot(aq, ab) / dot(ab, ab)).clamp(0.0, 1.0);
        let r = sub(aq, ab.map(|c| c * t));
        if dot(r, r).sqrt() <= tol {
            return true;
        }
    }
    // Inside: crossing test in the plane that drops the normal's largest axis.
    let drop = (0..3).max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs())).unwrap_or(2);
    let (u, v) = ((drop + 1) % 3, (drop + 2) % 3);
    let mut inside = false;
    for (a, b) in p.iter().zip(p.iter().cycle().skip(1)) {
        if (a[v] > q[v]) != (b[v] > q[v]) {
            let x = a[u] + (q[v] - a[v]) / (b[v] - a[v]) * (b[u] - a[u]);
            if q[u] < x {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{BuildOptions, CellKind, build_map};

    #[test]
    fn hanging_vertex_is_found() {
        // Two unit cubes side by side: conformal.
        let mut m = crate::generate::hex_grid(2, 1, 1);
        let (map, _) = build_map(m.clone(), &BuildOptions::default()).expect("grid");
        assert_eq!(non_conformal_faces(&map), 0);
        // A cell on top of the second half of the first cube: its corners at x = 0.5
        // hang on the first cube's top edges, seen by its top, front and back faces.
        let id = |i: u32, j: u32, k: u32| i + 3 * (j + 2 * k);
        let base = m.points.len() as u32;
        m.points.extend([[0.5, 0., 1.], [0.5, 1., 1.], [0.5, 0., 2.], [1., 0., 2.], [1., 1., 2.], [0.5, 1., 2.]]);
        let nodes = [base, id(1, 0, 1), id(1, 1, 1), base + 1, base + 2, base + 3, base + 4, base + 5];
        m.push_cell(CellKind::Hex, &nodes, None);
        let (map, _) = build_map(m, &BuildOptions::default()).expect("three cells");
        assert_eq!(non_conformal_faces(&map), 3);
    }
}
