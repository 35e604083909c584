//! Cell counts, boundary, connected components and Euler characteristic.

use super::orbit::Orbit;
use super::storage::CMap3;

/// Number of cells of each dimension, as counted by [`CMap3::count_cells`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CellCounts {
    pub darts: usize,
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub volumes: usize,
    pub components: usize,
}

impl CellCounts {
    /// V − E + F − C for volume maps, V − E + F for surface maps.
    pub fn euler_characteristic(&self, dimension: u8) -> i64 {
        let (v, e, f, c) = (self.vertices as i64, self.edges as i64, self.faces as i64, self.volumes as i64);
        if dimension == 3 { v - e + f - c } else { v - e + f }
    }
}

impl CMap3 {
    /// Counts vertices, edges, faces, volumes and connected components.
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, (i * i) as f64, (i * i * i) as f64])).collect();
    /// m.make_tetrahedron([v[0], v[1], v[2], v[3]]);
    /// let c = m.count_cells();
    /// assert_eq!((c.vertices, c.edges, c.faces, c.volumes), (4, 6, 4, 1));
    /// assert_eq!(m.euler_characteristic(), 1);
    /// ```
    pub fn count_cells(&self) -> CellCounts {
        CellCounts {
            darts: self.nb_darts(),
            vertices: self.cells(Orbit::Vertex).count(),
            edges: self.cells(Orbit::Edge).count(),
            faces: self.cells(Orbit::Face).count(),
            volumes: self.cells(Orbit::Volume).count(),
            components: self.cells(Orbit::Component).count(),
        }
    }

    /// Euler characteristic (see [`CellCounts::euler_characteristic`]).
    pub fn euler_characteristic(&self) -> i64 {
        self.count_cells().euler_characteristic(self.dimension)
    }

    /// Faces lying on the boundary of a volume map (3-free faces).
    pub fn boundary_faces(&self) -> usize {
        self.cells(Orbit::HalfFace).filter(|&d| self.is_free(d, 3)).count()
    }

    /// Boundary edges of a surface map (2-free darts).
    pub fn boundary_edges(&self) -> usize {
        self.darts().filter(|&d| self.is_free(d, 2)).count()
    }

    /// Number of connected components.
    pub fn connected_components(&self) -> usize {
        self.cells(Orbit::Component).count()
    }
}
