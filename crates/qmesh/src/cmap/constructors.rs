//! Cell constructors: polygons and the standard volume cells (2022 §2.2).
//!
//! Node orders are VTK's (GUIDE §3); faces are created with the map's orientation
//! convention (β1 clockwise seen from outside, see [`CMap3`]).

use super::dart::Dart;
use super::error::MapError;
use super::storage::CMap3;

/// Face cycles of the standard cells in map orientation, as VTK node indices.
pub mod faces {
    /// VTK tetrahedron (type 10): 0-1-2 has its normal toward 3.
    pub const TET: &[&[usize]] = &[&[0, 1, 2], &[1, 0, 3], &[2, 1, 3], &[0, 2, 3]];
    /// VTK pyramid (type 14): base 0-1-2-3 has its normal toward apex 4.
    pub const PYRAMID: &[&[usize]] = &[&[0, 1, 2, 3], &[1, 0, 4], &[2, 1, 4], &[3, 2, 4], &[0, 3, 4]];
    /// VTK wedge (type 13): 0-1-2 has its normal pointing *away* from 3-4-5.
    pub const PRISM: &[&[usize]] = &[&[0, 2, 1], &[3, 4, 5], &[0, 1, 4, 3], &[1, 2, 5, 4], &[2, 0, 3, 5]];
    /// VTK hexahedron (type 12): base 0-1-2-3 has its normal toward 4-5-6-7.
    pub const HEX: &[&[usize]] =
        &[&[0, 1, 2, 3], &[1, 0, 4, 5], &[2, 1, 5, 6], &[3, 2, 6, 7], &[0, 3, 7, 4], &[7, 6, 5, 4]];
}

impl CMap3 {
    /// Creates an isolated face whose β1 cycle visits `vertices` in order (β2, β3 free);
    /// returns the dart starting at `vertices[0]`.
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// m.set_dimension(2);
    /// let v: Vec<u32> = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].iter().map(|p| m.add_vertex(*p)).collect();
    /// let d = m.make_polygon(&v);
    /// assert_eq!(m.vertex_of(m.next(d)), v[1]);
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Panics
    /// If `vertices` is empty.
    pub fn make_polygon(&mut self, vertices: &[u32]) -> Dart {
        assert!(!vertices.is_empty(), "a polygon needs vertices");
        let first = self.create_dart(vertices[0]);
        let mut prev = first;
        for &v in &vertices[1..] {
            let d = self.create_dart(v);
            self.link(prev, 1, d);
            prev = d;
        }
        self.link(prev, 1, first);
        first
    }

    /// Creates a closed volume from face cycles (each list is the β1 cycle of one face, in
    /// map orientation) and 2-sews every directed edge u→v to the edge v→u.
    /// Returns the first dart of the first face.
    ///
    /// ```
    /// use qmesh::cmap::{CMap3, Orbit};
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = [[0.,0.,0.],[1.,0.,0.],[0.,1.,0.],[0.,0.,1.]].iter().map(|p| m.add_vertex(*p)).collect();
    /// let faces = [vec![v[0], v[1], v[2]], vec![v[1], v[0], v[3]], vec![v[2], v[1], v[3]], vec![v[0], v[2], v[3]]];
    /// let d = m.make_polyhedron(&faces).unwrap();
    /// assert_eq!(m.orbit(d, Orbit::Volume).len(), 12);
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Errors
    /// A face with fewer than 3 vertices, an edge without its opposite (open
    /// polyhedron) or an edge used twice in the same direction (non-manifold or
    /// inconsistently oriented faces). The map is unchanged on error.
    pub fn make_polyhedron<F: AsRef<[u32]>>(&mut self, faces: &[F]) -> Result<Dart, MapError> {
        Ok(self.make_polyhedron_faces(faces)?[0])
    }

    /// As [`make_polyhedron`](Self::make_polyhedron), returning the first dart of each
    /// face (the dart starting at the face's first vertex), in the order given.
    ///
    /// # Errors
    /// As [`make_polyhedron`](Self::make_polyhedron).
    pub fn make_polyhedron_faces<F: AsRef<[u32]>>(&mut self, faces: &[F]) -> Result<Vec<Dart>, MapError> {
        if faces.is_empty() {
            return Err(MapError::FaceTooSmall { min: 3, got: 0 });
        }
        let mut edges: Vec<(u32, u32, usize)> = Vec::new();
        for f in faces {
            let f = f.as_ref();
            if f.len() < 3 {
                return Err(MapError::FaceTooSmall { min: 3, got: f.len() });
            }
            for k in 0..f.len() {
                edges.push((f[k], f[(k + 1) % f.len()], edges.len()));
            }
        }
        // Pair u→v with v→u: sort by the undirected key, then check each group is one pair.
        let mut keyed: Vec<(u32, u32, usize)> = edges.iter().map(|&(u, v, i)| (u.min(v), u.max(v), i)).collect();
        keyed.sort_unstable();
        let mut pairs = Vec::with_capacity(edges.len() / 2);
        let mut k = 0;
        while k < keyed.len() {
            let (a, b, i) = keyed[k];
            let same = |j: usize| j < keyed.len() && keyed[j].0 == a && keyed[j].1 == b;
            let (u, v, _) = edges[i];
            if !same(k + 1) {
                return Err(MapError::OpenPolyhedron(u, v));
            }
            let j = keyed[k + 1].2;
            if same(k + 2) || edges[j].0 == u {
                return Err(MapError::NonManifoldPolyhedron(u, v));
            }
            pairs.push((i, j));
            k += 2;
        }
        let mut darts = Vec::with_capacity(edges.len());
        let mut firsts = Vec::with_capacity(faces.len());
        for f in faces {
            let d0 = self.make_polygon(f.as_ref());
            firsts.push(d0);
            let mut d = d0;
            loop {
                darts.push(d);
                d = self.next(d);
                if d == d0 {
                    break;
                }
            }
        }
        for (i, j) in pairs {
            self.link(darts[i], 2, darts[j]);
        }
        Ok(firsts)
    }

    fn make_standard(&mut self, table: &[&[usize]], nodes: &[u32]) -> Dart {
        let faces: Vec<Vec<u32>> = table.iter().map(|f| f.iter().map(|&k| nodes[k]).collect()).collect();
        self.make_polyhedron(&faces).expect("standard cell tables are closed and manifold")
    }

    /// A tetrahedron on vertex ids in VTK order (12 darts). Returns the dart 0→1.
    pub fn make_tetrahedron(&mut self, n: [u32; 4]) -> Dart {
        self.make_standard(faces::TET, &n)
    }

    /// A pyramid on vertex ids in VTK order (16 darts). Returns the dart 0→1.
    pub fn make_pyramid(&mut self, n: [u32; 5]) -> Dart {
        self.make_standard(faces::PYRAMID, &n)
    }

    /// A prism (VTK wedge) on vertex ids in VTK order (18 darts). Returns the dart 0→2.
    pub fn make_prism(&mut self, n: [u32; 6]) -> Dart {
        self.make_standard(faces::PRISM, &n)
    }

    /// A hexahedron on vertex ids in VTK order (24 darts). Returns the dart 0→1.
    pub fn make_hexahedron(&mut self, n: [u32; 8]) -> Dart {
        self.make_standard(faces::HEX, &n)
    }
}
