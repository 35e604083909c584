//! Edge splitting: insert a vertex in an edge; the e-pattern (2022 §4.1).

use super::dart::Dart;
use super::error::MapError;
use super::orbit::Orbit;
use super::storage::CMap3;
use smallvec::SmallVec;

impl CMap3 {
    /// Inserts a new vertex at `p` in the edge of `d`. Every dart around the edge (across
    /// β2 and β3) is split in two; the part starting at the original vertex keeps the
    /// dart and its marks, the new part is unmarked (the papers' flag rule, 2022 §3).
    /// Returns the new dart that follows `d` in its face (it starts at the new vertex).
    ///
    /// ```
    /// use qmesh::cmap::{CMap3, Orbit};
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = (0..8).map(|i| m.add_vertex([(i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64])).collect();
    /// let d = m.make_hexahedron([v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]]);
    /// let n = m.insert_vertex_in_edge(d, [0.5, 0.0, 0.0]);
    /// assert_eq!(m.nb_darts(), 26);
    /// assert_eq!(m.point(n), [0.5, 0.0, 0.0]);
    /// assert!(m.is_valid().is_empty());
    /// ```
    pub fn insert_vertex_in_edge(&mut self, d: Dart, p: [f64; 3]) -> Dart {
        let v = self.add_vertex(p);
        // Edges of volume meshes have a few darts: kept inline, no allocation per edge.
        let edge: SmallVec<[Dart; 16]> =
            self.with_scratch(|m, w| w.collect(m, d, Orbit::Edge).iter().copied().collect());
        let new: SmallVec<[Dart; 16]> = edge.iter().map(|_| self.create_dart(v)).collect();
        let new_of = |x: Dart| new[edge.iter().position(|&e| e == x).expect("edge orbit is closed under β2, β3")];
        // Read the old β2/β3 partners before rewiring anything.
        let partners: SmallVec<[[Option<Dart>; 2]; 16]> =
            edge.iter().map(|&x| [self.beta(x, 2), self.beta(x, 3)]).collect();
        for (k, &x) in edge.iter().enumerate() {
            let n = new[k];
            self.set_label_of(n, self.label_of(x));
            let after = self.next(x);
            self.link(n, 1, after);
            self.link(x, 1, n);
            for (slot, i) in [(0, 2), (1, 3)] {
                if let Some(o) = partners[k][slot] {
                    // x: a→m pairs with the new half of o (m→a); n: m→b pairs with o (b→m).
                    let (no, nx) = (new_of(o), n);
                    self.betas[x.idx()][i] = no.raw();
                    self.betas[nx.idx()][i] = o.raw();
                }
            }
        }
        new[0]
    }

    /// Splits the edge of `d` into `k` equal segments (the e-pattern, 2022 §4.1) and
    /// returns the `k - 1` new darts along `d`'s side, in order from d's origin.
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = [[0., 0., 0.], [3., 0., 0.], [0., 3., 0.], [0., 0., 3.]].iter().map(|p| m.add_vertex(*p)).collect();
    /// let d = m.make_tetrahedron([v[0], v[1], v[2], v[3]]); // d runs 0 → 1
    /// let new = m.split_edge(d, 3).unwrap();
    /// assert_eq!((m.point(new[0]), m.point(new[1])), ([1., 0., 0.], [2., 0., 0.]));
    /// assert_eq!(m.count_cells().edges, 8);
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Errors
    /// [`MapError::BadSegmentCount`] when `k == 0`.
    pub fn split_edge(&mut self, d: Dart, k: usize) -> Result<Vec<Dart>, MapError> {
        self.err_if_dead(d)?;
        if k == 0 {
            return Err(MapError::BadSegmentCount(k));
        }
        let a = self.point(d);
        let b = self.point(self.next(d));
        let mut cur = d;
        let mut out = Vec::with_capacity(k - 1);
        for i in 1..k {
            let t = i as f64 / k as f64;
            let p = [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t];
            cur = self.insert_vertex_in_edge(cur, p);
            out.push(cur);
        }
        Ok(out)
    }

    /// Splits every edge of the map into `k` segments; returns the number of edges split.
    pub fn split_all_edges(&mut self, k: usize) -> Result<usize, MapError> {
        let reps: Vec<Dart> = self.cells(Orbit::Edge).collect();
        for &d in &reps {
            self.split_edge(d, k)?;
        }
        Ok(reps.len())
    }
}
