//! The boundary surface of indexed volume cells, for writing a volume mesh to a surface
//! format (OFF, OBJ, STL, PLY).

use rustc_hash::FxHashMap;

use super::IndexedMesh;

impl IndexedMesh {
    /// The surface a surface format can hold: this mesh's polygons, plus every cell
    /// face that no other cell shares (outward, as the cells are oriented), on the
    /// points those use (renumbered in order of first use). A surface mesh is returned
    /// as it is. Faces of a malformed polyhedron stream are left out.
    ///
    /// ```
    /// use qmesh::build::{CellKind, IndexedMesh};
    /// let mut m = IndexedMesh::new();
    /// m.points = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [1., 1., 1.]];
    /// m.push_cell(CellKind::Tet, &[0, 1, 2, 3], None);
    /// m.push_cell(CellKind::Tet, &[1, 2, 3, 4], None);
    /// let s = m.boundary_surface();
    /// assert_eq!(s.nb_polygons(), 6); // 2 × 4 faces, the shared one twice removed
    /// assert_eq!(s.points.len(), 5);
    /// ```
    pub fn boundary_surface(&self) -> IndexedMesh {
        if !self.is_volume() {
            return self.clone();
        }
        let faces: Vec<Vec<u32>> = (0..self.nb_cells()).filter_map(|i| self.cell_faces(i)).flatten().collect();
        let key = |f: &[u32]| {
            let mut k = f.to_vec();
            k.sort_unstable();
            k
        };
        let mut count: FxHashMap<Vec<u32>, u32> = FxHashMap::default();
        for f in &faces {
            *count.entry(key(f)).or_insert(0) += 1;
        }
        let mut out = IndexedMesh::new();
        let mut new_id = vec![u32::MAX; self.points.len()];
        let mut push = |out: &mut IndexedMesh, nodes: &mut dyn Iterator<Item = u32>| {
            let p: Vec<u32> = nodes
                .map(|v| {
                    if new_id[v as usize] == u32::MAX {
                        new_id[v as usize] = out.points.len() as u32;
                        out.points.push(self.points[v as usize]);
                    }
                    new_id[v as usize]
                })
                .collect();
            out.push_polygon(&p);
        };
        for i in 0..self.nb_polygons() {
            push(&mut out, &mut self.polygon(i).iter().copied());
        }
        // Cell faces are stored with inward normals (map orientation): reverse them.
        for f in faces.iter().filter(|f| count[&key(f)] == 1) {
            push(&mut out, &mut f.iter().rev().copied());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::CellKind;

    #[test]
    fn a_hexahedron_has_six_outward_quads() {
        let mut m = IndexedMesh::new();
        m.points = crate::build::HEX_CORNER_BITS
            .iter()
            .map(|&b| [f64::from(b & 1), f64::from(b >> 1 & 1), f64::from(b >> 2 & 1)])
            .collect();
        m.push_cell(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7], None);
        let s = m.boundary_surface();
        assert_eq!(s.nb_polygons(), 6);
        // Outward: the signed volume enclosed by the faces is positive.
        let mut volume = 0.0;
        for i in 0..s.nb_polygons() {
            let p = s.polygon(i);
            for k in 1..p.len() - 1 {
                let (a, b, c) = (s.points[p[0] as usize], s.points[p[k] as usize], s.points[p[k + 1] as usize]);
                volume += crate::geom::dot(a, crate::geom::cross(b, c)) / 6.0;
            }
        }
        assert!((volume - 1.0).abs() < 1e-12, "{volume}");
    }
}
