//! Reversing the orientation of a whole map.

use super::storage::CMap3;

impl CMap3 {
    /// Reverses the orientation of every cell: β0 and β1 swap and each dart's origin
    /// becomes its former target; β2 and β3 are unchanged. A valid map stays valid.
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, (i * i) as f64, (i * i * i) as f64])).collect();
    /// let d = m.make_tetrahedron([v[0], v[1], v[2], v[3]]);
    /// m.reverse_orientation();
    /// // d ran 0 → 1; it now runs 1 → 0, and its successor starts at 0.
    /// assert_eq!((m.vertex_of(d), m.vertex_of(m.next(d))), (v[1], v[0]));
    /// assert!(m.is_valid().is_empty());
    /// ```
    pub fn reverse_orientation(&mut self) {
        let targets: Vec<u32> = (0..self.betas.len())
            .map(|i| {
                let n = self.betas[i][1];
                if i == 0 || n == 0 { self.vertex[i] } else { self.vertex[n as usize] }
            })
            .collect();
        for (i, b) in self.betas.iter_mut().enumerate() {
            if i > 0 {
                b.swap(0, 1);
            }
        }
        self.vertex = targets;
    }
}
