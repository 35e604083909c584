//! Built-in inputs: structured hexahedral grids and their tetrahedral splits, a torus
//! surface, and voxel terrains.

mod terrain;

pub use terrain::{TerrainOptions, height_map, terrain, terrain_map};

use crate::build::{CellKind, IndexedMesh};

/// An `nx × ny × nz` grid of unit-spaced hexahedra over `[0, nx] × [0, ny] × [0, nz]`.
///
/// ```
/// let g = qmesh::generate::hex_grid(2, 3, 4);
/// assert_eq!((g.nb_cells(), g.points.len()), (24, 3 * 4 * 5));
/// ```
pub fn hex_grid(nx: usize, ny: usize, nz: usize) -> IndexedMesh {
    let mut m = IndexedMesh::new();
    let id = |i: usize, j: usize, k: usize| (i + (nx + 1) * (j + (ny + 1) * k)) as u32;
    m.points.reserve((nx + 1) * (ny + 1) * (nz + 1));
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                m.points.push([i as f64, j as f64, k as f64]);
            }
        }
    }
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let n = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                m.push_cell(CellKind::Hex, &n, None);
            }
        }
    }
    m
}

/// The grid of [`hex_grid`] with every hexahedron split into 6 tetrahedra around its
/// 0–6 diagonal (Kuhn split: conforming across faces because every cell is split the
/// same way).
pub fn tet_grid(nx: usize, ny: usize, nz: usize) -> IndexedMesh {
    let hexes = hex_grid(nx, ny, nz);
    let mut m = IndexedMesh { points: hexes.points.clone(), ..IndexedMesh::new() };
    // Paths 0 → 6 through the cube's vertices, each giving one tet (VTK positive order).
    const KUHN: [[usize; 4]; 6] = [[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6], [0, 5, 1, 6]];
    for c in 0..hexes.nb_cells() {
        let h = hexes.cell(c).1;
        for t in KUHN {
            m.push_cell(CellKind::Tet, &t.map(|k| h[k]), None);
        }
    }
    m
}

/// A triangulated torus around the z axis (major radius `big`, minor `small`), `nu`
/// segments around z and `nv` around the tube, outward normals.
pub fn torus_surface(big: f64, small: f64, nu: usize, nv: usize) -> IndexedMesh {
    let mut m = IndexedMesh::new();
    let tau = std::f64::consts::TAU;
    for i in 0..nu {
        let u = tau * i as f64 / nu as f64;
        for j in 0..nv {
            let v = tau * j as f64 / nv as f64;
            let r = big + small * v.cos();
            m.points.push([r * u.cos(), r * u.sin(), small * v.sin()]);
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + j % nv) as u32;
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            m.push_polygon(&[a, b, c]);
            m.push_polygon(&[a, c, d]);
        }
    }
    m
}
