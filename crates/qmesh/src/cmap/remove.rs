//! Removal of a face between two volumes (merging them, 2025 §6.3) and of a volume.

use super::dart::Dart;
use super::error::MapError;
use super::orbit::Orbit;
use super::storage::CMap3;

impl CMap3 {
    /// Removes the face of `d`, which separates two volumes, merging them into one:
    /// for each dart x of the face, β2(x) is 2-sewn to β2(β3(x)).
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
                Some(o) if !both.contains(&o) => {}
                _ => return Err(MapError::DegenerateFace(d)),
            }
        }
        let links: Vec<(Dart, Dart)> =
            side.iter().map(|&x| (self.beta(x, 2).unwrap(), self.beta(self.beta(x, 3).unwrap(), 2).unwrap())).collect();
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
        self.err_if_dead(d)?;
        let vol: Vec<Dart> = self.with_scratch(|m, w| w.collect(m, d, Orbit::Volume).to_vec());
        let mut touched = Vec::new();
        for &x in &vol {
            if let Some(o) = self.beta(x, 3) {
                self.unlink(x, 3);
                touched.push(o);
            }
        }
        for &x in &vol {
            self.delete_dart(x);
        }
        self.split_vertex_ids(&touched);
        Ok(vol.len())
    }
}
