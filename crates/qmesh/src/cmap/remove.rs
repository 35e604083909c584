//! Removal of a face between two volumes (merging them, 2025 §6.3), of an edge between
//! two faces (merging them) and of a volume.

use super::bitset::BitSet;
use super::dart::Dart;
use super::error::MapError;
use super::orbit::{Orbit, OrbitWalker};
use super::storage::CMap3;
use rayon::prelude::*;

impl CMap3 {
    /// Removes the face of `d`, which separates two volumes, merging them into one:
    /// for each dart x of the face, β2(x) is 2-sewn to β2(β3(x)). An edge that only
    /// this face bounds inside the merged volume (β2(x) = β3(x): the last face around an
    /// inner edge when several volumes are merged one face at a time) goes with it.
    ///
    /// ```
    /// use qmesh::cmap::{CMap3, Orbit};
    /// let mut m = CMap3::new();
    /// let p = |m: &mut CMap3, x: f64, y: f64, z: f64| m.add_vertex([x, y, z]);
    /// let (a, b, c, t, u) = (p(&mut m, 0., 0., 0.), p(&mut m, 1., 0., 0.), p(&mut m, 0., 1., 0.), p(&mut m, 0., 0., 1.), p(&mut m, 0., 0., -1.));
    /// let d1 = m.make_tetrahedron([a, b, c, t]);
    /// let d2 = m.make_tetrahedron([a, c, b, u]);
    /// let d2 = m.prev(d2);
    /// m.sew3(d1, d2).unwrap();
    /// m.remove_face(d1).unwrap();
    /// assert_eq!(m.cells(Orbit::Volume).count(), 1);
    /// assert_eq!(m.nb_darts(), 18);
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Errors
    /// [`MapError::FaceOnBoundary`] when the face is 3-free anywhere;
    /// [`MapError::DegenerateFace`] when an edge of the face is 2-sewn inside the face.
    pub fn remove_face(&mut self, d: Dart) -> Result<(), MapError> {
        self.err_if_dead(d)?;
        let side: Vec<Dart> = self.with_scratch(|m, w| w.collect(m, d, Orbit::HalfFace).to_vec());
        let mut both = Vec::with_capacity(side.len() * 2);
        for &x in &side {
            both.push(x);
            both.push(self.beta(x, 3).ok_or(MapError::FaceOnBoundary(d))?);
        }
        for &x in &both {
            match self.beta(x, 2) {
                Some(o) if !both.contains(&o) || Some(o) == self.beta(x, 3) => {}
                _ => return Err(MapError::DegenerateFace(d)),
            }
        }
        let links: Vec<(Dart, Dart)> = side
            .iter()
            .filter(|&&x| self.beta(x, 2) != self.beta(x, 3))
            .map(|&x| (self.beta(x, 2).unwrap(), self.beta(self.beta(x, 3).unwrap(), 2).unwrap()))
            .collect();
        for &x in &both {
            self.delete_dart(x);
        }
        let mut touched = Vec::with_capacity(links.len() * 4);
        for &(a, b) in &links {
            self.link(a, 2, b);
            touched.extend([a, b, self.next(a), self.next(b)]);
        }
        // Vertices that were joined only through the removed face come apart.
        self.split_vertex_ids(&touched);
        Ok(())
    }

    /// Removes the edge of `d` when exactly two faces meet there (in each volume along
    /// it), merging them into one face: the diagonal of a quadrilateral split in two
    /// triangles, between two volumes or on the boundary. A dangling edge (both sides in
    /// one face, one end met by no other edge: what is left of an inner vertex when the
    /// faces around it are merged one edge at a time) is removed with that end.
    ///
    /// ```
    /// use qmesh::build::{BuildOptions, CellKind, IndexedMesh, build_volume_map};
    /// let mut mesh = IndexedMesh::new();
    /// mesh.points = vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [0., 0., 1.]];
    /// // A square pyramid split in two tetrahedra along the base diagonal 0-2.
    /// mesh.push_cell(CellKind::Tet, &[0, 1, 2, 4], None);
    /// mesh.push_cell(CellKind::Tet, &[0, 2, 3, 4], None);
    /// let (mut m, _) = build_volume_map(&mesh, &BuildOptions::default()).unwrap();
    /// let on_diagonal = |m: &qmesh::cmap::CMap3, d| {
    ///     let mut e = [m.vertex_of(d), m.vertex_of(m.next(d))];
    ///     e.sort();
    ///     e == [0, 2]
    /// };
    /// let inner = m.darts().find(|&d| on_diagonal(&m, d) && !m.is_free(d, 3)).unwrap();
    /// let base = m.darts().find(|&d| on_diagonal(&m, d) && m.is_free(d, 3)).unwrap();
    /// // Three faces meet at the diagonal: the two base triangles and the inner one.
    /// assert!(m.remove_edge(base).is_err());
    /// m.remove_face(inner).unwrap();
    /// m.remove_edge(base).unwrap();
    /// assert_eq!(m.nb_darts(), 16); // a pyramid with a quadrilateral base
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Errors
    /// [`MapError::EdgeNotRemovable`] when more than two faces meet at the edge, or the
    /// two are the same face.
    pub fn remove_edge(&mut self, d: Dart) -> Result<(), MapError> {
        self.err_if_dead(d)?;
        let e = self.beta(d, 2).ok_or(MapError::EdgeNotRemovable(d))?;
        let (d3, e3) = (self.beta(d, 3), self.beta(e, 3));
        let pairs: Vec<(Dart, Dart)> = match (d3, e3) {
            (None, None) => vec![(d, e)],
            (Some(x), Some(y)) if self.beta(x, 2) == Some(y) => vec![(d, e), (x, y)],
            _ => return Err(MapError::EdgeNotRemovable(d)),
        };
        let dangling = |m: &CMap3, x: Dart, y: Dart| m.next(x) == y || m.next(y) == x;
        for &(x, y) in &pairs {
            let removable = if dangling(self, x, y) {
                // Not an edge that is a whole face by itself.
                !(self.next(x) == y && self.next(y) == x)
            } else {
                !self.with_scratch(|m, w| w.collect(m, x, Orbit::HalfFace).contains(&y))
            };
            if !removable || dangling(self, x, y) != dangling(self, pairs[0].0, pairs[0].1) {
                return Err(MapError::EdgeNotRemovable(d));
            }
        }
        for &(x, y) in &pairs {
            let (px, nx, py, ny) = (self.prev(x), self.next(x), self.prev(y), self.next(y));
            self.delete_dart(x);
            self.delete_dart(y);
            if nx == y {
                self.link(px, 1, ny);
            } else if ny == x {
                self.link(py, 1, nx);
            } else {
                self.link(px, 1, ny);
                self.link(py, 1, nx);
            }
        }
        Ok(())
    }

    /// Removes the volume of `d`; its neighbours become 3-free there (boundary).
    /// Returns the number of darts removed.
    ///
    /// ```
    /// use qmesh::build::{BuildOptions, build_volume_map};
    /// let (mut m, _) = build_volume_map(&qmesh::generate::hex_grid(2, 1, 1), &BuildOptions::default()).unwrap();
    /// let first = m.darts().next().unwrap();
    /// assert_eq!(m.remove_volume(first).unwrap(), 24);
    /// assert_eq!((m.count_cells().volumes, m.boundary_faces()), (1, 6));
    /// assert!(m.is_valid().is_empty());
    /// ```
    pub fn remove_volume(&mut self, d: Dart) -> Result<usize, MapError> {
        self.remove_volumes(&[d])
    }

    /// Removes the volumes of `volumes` (a volume listed twice is removed once); their
    /// neighbours become 3-free there. The volumes' darts are gathered on all cores and
    /// the vertices that come apart are split once for all, so removing many volumes
    /// costs about what one pass over them does. Returns the number of darts removed.
    ///
    /// ```
    /// use qmesh::build::{BuildOptions, build_volume_map};
    /// use qmesh::cmap::Orbit;
    /// let (mut m, _) = build_volume_map(&qmesh::generate::hex_grid(3, 1, 1), &BuildOptions::default()).unwrap();
    /// let ends: Vec<_> = m.cells(Orbit::Volume).step_by(2).collect();
    /// assert_eq!(m.remove_volumes(&ends).unwrap(), 48);
    /// assert_eq!(m.count_cells().volumes, 1);
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Errors
    /// [`MapError::DeadDart`] when a dart of `volumes` is not in the map (nothing is removed).
    pub fn remove_volumes(&mut self, volumes: &[Dart]) -> Result<usize, MapError> {
        for &d in volumes {
            self.err_if_dead(d)?;
        }
        // Each chunk's volumes, one after the other, with where each one ends.
        let map = &*self;
        let gather = |c: &[Dart]| {
            let mut w = OrbitWalker::new();
            let (mut darts, mut ends) = (Vec::new(), Vec::with_capacity(c.len()));
            for &d in c {
                darts.extend_from_slice(w.collect(map, d, Orbit::Volume));
                ends.push(darts.len());
            }
            (darts, ends)
        };
        let chunks: Vec<(Vec<Dart>, Vec<usize>)> = if volumes.len() < 64 {
            vec![gather(volumes)]
        } else {
            volumes.par_chunks(volumes.len().div_ceil(4 * rayon::current_num_threads())).map(gather).collect()
        };
        let mut gone = BitSet::with_len(self.dart_capacity());
        let mut darts = Vec::with_capacity(chunks.iter().map(|c| c.0.len()).sum());
        for (all, ends) in &chunks {
            let mut start = 0;
            for &end in ends {
                let v = &all[start..end];
                start = end;
                if !gone.get(v[0].idx()) {
                    v.iter().for_each(|x| {
                        gone.insert(x.idx());
                    });
                    darts.extend_from_slice(v);
                }
            }
        }
        drop(chunks);
        // The neighbours across become 3-free; the removed darts' own links go with them.
        let map = &*self;
        let touched: Vec<Dart> = darts
            .par_iter()
            .with_min_len(1 << 12)
            .filter_map(|&x| map.beta(x, 3).filter(|o| !gone.get(o.idx())))
            .collect();
        for o in &touched {
            self.set_beta_raw(o.raw(), 3, 0);
        }
        self.delete_darts(&darts, &gone);
        self.split_vertex_ids(&touched);
        Ok(darts.len())
    }
}

#[cfg(test)]
mod tests {
    use crate::build::{BuildOptions, build_volume_map};
    use crate::cmap::{CMap3, Dart, Orbit};

    /// A 2×2×2 grid of cubes and its volumes by the corner of their box nearest the origin.
    fn grid() -> (CMap3, Vec<([i64; 3], Dart)>) {
        let (m, _) = build_volume_map(&crate::generate::hex_grid(2, 2, 2), &BuildOptions::default()).unwrap();
        let mut cells: Vec<([i64; 3], Dart)> = m
            .cells(Orbit::Volume)
            .map(|v| {
                let lo = m
                    .orbit(v, Orbit::Volume)
                    .iter()
                    .map(|&x| m.point(x))
                    .fold([f64::MAX; 3], |a, p| [0, 1, 2].map(|k| a[k].min(p[k])));
                (lo.map(|x| x.round() as i64), v)
            })
            .collect();
        cells.sort();
        (m, cells)
    }

    fn remove(m: &mut CMap3, cells: &[([i64; 3], Dart)], gone: impl Fn([i64; 3]) -> bool) {
        let darts: Vec<Dart> = cells.iter().filter(|c| gone(c.0)).map(|c| c.1).collect();
        m.remove_volumes(&darts).unwrap();
        assert!(m.is_valid().is_empty(), "{:?}", m.is_valid());
    }

    /// Removing many volumes at once (their slots cleared a stretch of the tables per
    /// core) leaves the same darts, links and free slots as removing them one by one.
    #[test]
    fn removing_together_equals_removing_one_by_one() {
        // 12³ cubes: 41,472 darts, so the slots cleared span several stretches.
        let (m, _) = build_volume_map(&crate::generate::hex_grid(12, 12, 12), &BuildOptions::default()).unwrap();
        let volumes: Vec<Dart> = m.cells(Orbit::Volume).collect();
        let chosen: Vec<Dart> = volumes.iter().enumerate().filter(|(i, _)| i * 7 % 11 < 5).map(|(_, &d)| d).collect();
        let (mut together, mut one_by_one) = (m.clone(), m);
        together.remove_volumes(&chosen).unwrap();
        chosen.iter().for_each(|&d| {
            one_by_one.remove_volume(d).unwrap();
        });
        assert!(together.is_valid().is_empty());
        assert_eq!(together.count_cells(), one_by_one.count_cells());
        for i in 1..together.dart_capacity() as u32 {
            let d = Dart::from_raw(i).unwrap();
            assert_eq!(together.is_live(d), one_by_one.is_live(d), "dart {i}");
            assert_eq!(together.betas_raw(i), one_by_one.betas_raw(i), "dart {i}");
        }
        // Freed slots are taken again in the same order.
        for _ in 0..chosen.len() * 24 {
            assert_eq!(together.create_dart(0), one_by_one.create_dart(0));
        }
    }

    /// Vertices joined only through removed volumes get ids of their own; the others
    /// keep theirs (the boundary walk around them proves it without the whole orbit).
    #[test]
    fn vertices_joined_only_through_removed_volumes_come_apart() {
        // One cube gone: the 26 other grid points stay single vertices.
        let (mut m, cells) = grid();
        remove(&mut m, &cells, |c| c == [0, 0, 0]);
        assert_eq!(m.count_cells().vertices, 26);
        // Two opposite cubes kept: they share the centre only, which comes apart.
        let (mut m, cells) = grid();
        remove(&mut m, &cells, |c| c != [0, 0, 0] && c != [1, 1, 1]);
        assert_eq!(m.count_cells().vertices, 16);
        assert_eq!(m.nb_vertex_ids(), 27 + 1);
        // Two cubes along a diagonal of one layer kept: the two ends of the shared edge
        // come apart, and each cube is a component with 8 vertices.
        let (mut m, cells) = grid();
        remove(&mut m, &cells, |c| c[2] == 1 || c[0] != c[1]);
        let counts = m.count_cells();
        assert_eq!((counts.components, counts.vertices), (2, 16));
        // Three cubes of one layer kept, in an L: every vertex stays whole.
        let (mut m, cells) = grid();
        remove(&mut m, &cells, |c| c[2] == 1 || c == [1, 1, 0]);
        assert_eq!(m.count_cells().vertices, 16);
    }
}
