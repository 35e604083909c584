//! Cell constructors: polygons and the standard volume cells (2022 §2.2).
//!
//! Node orders are VTK's (GUIDE §3); faces are created with the map's orientation
//! convention (β1 clockwise seen from outside, see [`CMap3`]).

use std::sync::OnceLock;

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

/// The standard cells, with VTK node orders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Standard {
    Tet,
    Pyramid,
    Prism,
    Hex,
}

/// Where each dart of a standard cell starts and which darts are 2-sewn, computed
/// once per kind from its face table.
#[derive(Debug)]
pub struct Layout {
    /// Node (index into the cell's node list) at the origin of each dart.
    pub origin: Vec<u8>,
    /// `face_start[f]..face_start[f + 1]` are the darts of face f.
    pub face_start: Vec<u8>,
    /// Pairs of local darts that are 2-sewn.
    pub pairs: Vec<(u8, u8)>,
    /// `edge[i][j]` = 1 + the local dart running from node i to node j (0: none).
    pub edge: [[u8; 8]; 8],
    /// Local [β0, β1, β2] of each dart.
    pub local_betas: Vec<[u8; 3]>,
    /// A local dart starting at each node.
    pub node_dart: [u8; 8],
}

impl Layout {
    /// The local dart running from node `i` to node `j`, if the cell has that edge.
    #[inline]
    pub fn dart_of_edge(&self, i: usize, j: usize) -> Option<usize> {
        (self.edge[i][j] as usize).checked_sub(1)
    }

    /// A local dart starting at node `n`.
    #[inline]
    pub fn dart_of_node(&self, n: usize) -> usize {
        self.node_dart[n] as usize
    }

    /// Number of darts of face `f`.
    #[inline]
    pub fn face_len(&self, f: usize) -> usize {
        (self.face_start[f + 1] - self.face_start[f]) as usize
    }
}

impl Standard {
    pub const ALL: [Standard; 4] = [Standard::Tet, Standard::Pyramid, Standard::Prism, Standard::Hex];

    /// Face cycles in map orientation as node indices.
    pub fn faces(self) -> &'static [&'static [usize]] {
        match self {
            Standard::Tet => faces::TET,
            Standard::Pyramid => faces::PYRAMID,
            Standard::Prism => faces::PRISM,
            Standard::Hex => faces::HEX,
        }
    }

    /// Number of nodes.
    pub fn nodes(self) -> usize {
        match self {
            Standard::Tet => 4,
            Standard::Pyramid => 5,
            Standard::Prism => 6,
            Standard::Hex => 8,
        }
    }

    /// The cached dart layout of this kind.
    pub fn layout(self) -> &'static Layout {
        static LAYOUTS: OnceLock<Vec<Layout>> = OnceLock::new();
        let all = LAYOUTS.get_or_init(|| Standard::ALL.iter().map(|k| Layout::of(k.faces())).collect());
        &all[self as usize]
    }
}

impl Layout {
    fn of(table: &[&[usize]]) -> Layout {
        let mut origin = Vec::new();
        let mut face_start = vec![0u8];
        let mut edge = Vec::new();
        for f in table {
            for k in 0..f.len() {
                edge.push((f[k], f[(k + 1) % f.len()]));
                origin.push(f[k] as u8);
            }
            face_start.push(origin.len() as u8);
        }
        let mut pairs = Vec::new();
        let mut by_edge = [[0u8; 8]; 8];
        for (i, &(u, v)) in edge.iter().enumerate() {
            by_edge[u][v] = i as u8 + 1;
            let j = edge.iter().position(|&e| e == (v, u)).expect("standard cells are closed");
            if i < j {
                pairs.push((i as u8, j as u8));
            }
        }
        let mut local_betas = vec![[0u8; 3]; origin.len()];
        for f in 0..face_start.len() - 1 {
            let (a, b) = (face_start[f], face_start[f + 1]);
            for k in a..b {
                let next = if k + 1 == b { a } else { k + 1 };
                local_betas[k as usize][1] = next;
                local_betas[next as usize][0] = k;
            }
        }
        for &(i, j) in &pairs {
            local_betas[i as usize][2] = j;
            local_betas[j as usize][2] = i;
        }
        let mut node_dart = [0u8; 8];
        for (k, &o) in origin.iter().enumerate().rev() {
            node_dart[o as usize] = k as u8;
        }
        Layout { origin, face_start, pairs, edge: by_edge, local_betas, node_dart }
    }
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

    /// Creates a standard cell from its cached dart layout (no allocation) and returns
    /// its darts in layout order: face by face, as listed in the kind's face table.
    pub fn make_standard_cell(&mut self, kind: Standard, nodes: &[u32], out: &mut [u32; 24]) -> usize {
        let l = kind.layout();
        if self.free_darts.is_empty() {
            // Fast path: append one contiguous block with all its links at once.
            let base = self.append_cell(l, nodes);
            for (k, slot) in out.iter_mut().take(l.origin.len()).enumerate() {
                *slot = base + k as u32;
            }
            return l.origin.len();
        }
        for (k, &node) in l.origin.iter().enumerate() {
            out[k] = self.create_dart(nodes[node as usize]).raw();
        }
        let dart = |i: u32| Dart::from_raw(i).expect("created darts are not ε");
        for f in 0..l.face_start.len() - 1 {
            let (a, b) = (l.face_start[f] as usize, l.face_start[f + 1] as usize);
            for k in a..b {
                let next = if k + 1 == b { a } else { k + 1 };
                self.link(dart(out[k]), 1, dart(out[next]));
            }
        }
        for &(i, j) in &l.pairs {
            self.link(dart(out[i as usize]), 2, dart(out[j as usize]));
        }
        l.origin.len()
    }

    fn make_standard(&mut self, kind: Standard, nodes: &[u32]) -> Dart {
        let mut out = [0u32; 24];
        self.make_standard_cell(kind, nodes, &mut out);
        Dart::from_raw(out[0]).expect("created darts are not ε")
    }

    /// A tetrahedron on vertex ids in VTK order (12 darts). Returns the dart 0→1.
    pub fn make_tetrahedron(&mut self, n: [u32; 4]) -> Dart {
        self.make_standard(Standard::Tet, &n)
    }

    /// A pyramid on vertex ids in VTK order (16 darts). Returns the dart 0→1.
    pub fn make_pyramid(&mut self, n: [u32; 5]) -> Dart {
        self.make_standard(Standard::Pyramid, &n)
    }

    /// A prism (VTK wedge) on vertex ids in VTK order (18 darts). Returns the dart 0→2.
    pub fn make_prism(&mut self, n: [u32; 6]) -> Dart {
        self.make_standard(Standard::Prism, &n)
    }

    /// A hexahedron on vertex ids in VTK order (24 darts). Returns the dart 0→1.
    pub fn make_hexahedron(&mut self, n: [u32; 8]) -> Dart {
        self.make_standard(Standard::Hex, &n)
    }
}
