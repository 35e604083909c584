//! `compact`: renumber live darts contiguously and drop unused vertex ids.

use super::storage::CMap3;

/// Old → new index tables produced by [`CMap3::compact`] (0 = removed).
#[derive(Clone, Debug)]
pub struct Compaction {
    pub darts: Vec<u32>,
    pub vertices: Vec<u32>,
}

impl CMap3 {
    /// Renumbers live darts 1..=n in their current order, empties the free list, and
    /// keeps only the vertex ids some dart uses (in increasing order). Side tables
    /// indexed by dart or vertex id can be remapped with the returned tables.
    ///
    /// ```
    /// use qmesh::build::{BuildOptions, build_volume_map};
    /// let (mut m, _) = build_volume_map(&qmesh::generate::hex_grid(2, 1, 1), &BuildOptions::default()).unwrap();
    /// let first = m.darts().next().unwrap();
    /// m.remove_volume(first).unwrap();
    /// let table = m.compact();
    /// assert_eq!(table.darts[first.idx()], 0); // removed
    /// assert_eq!((m.nb_darts(), m.dart_capacity(), m.nb_vertex_ids()), (24, 25, 8));
    /// assert!(m.is_valid().is_empty());
    /// ```
    pub fn compact(&mut self) -> Compaction {
        let n = self.dart_capacity();
        let mut dmap = vec![0u32; n];
        let mut next = 1u32;
        for d in self.darts() {
            dmap[d.idx()] = next;
            next += 1;
        }
        let mut vused = vec![false; self.positions.len()];
        for d in self.darts() {
            vused[self.vertex[d.idx()] as usize] = true;
        }
        let mut vmap = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::with_capacity(vused.iter().filter(|u| **u).count());
        for (v, used) in vused.iter().enumerate() {
            if *used {
                vmap[v] = positions.len() as u32;
                positions.push(self.positions[v]);
            }
        }
        let mut betas = Vec::with_capacity(next as usize);
        let mut vertex = Vec::with_capacity(next as usize);
        let has_marks = !self.marks.is_empty();
        let mut marks = Vec::with_capacity(if has_marks { next as usize } else { 0 });
        betas.push([0; 4]);
        vertex.push(super::storage::DEAD);
        if has_marks {
            marks.push(0);
        }
        for i in 1..n {
            if dmap[i] == 0 {
                continue;
            }
            let b = self.betas[i];
            betas.push([dmap[b[0] as usize], dmap[b[1] as usize], dmap[b[2] as usize], dmap[b[3] as usize]]);
            vertex.push(vmap[self.vertex[i] as usize]);
            if has_marks {
                marks.push(self.marks[i]);
            }
        }
        self.betas = betas;
        self.vertex = vertex;
        self.marks = marks;
        self.positions = positions;
        self.free_darts = Vec::new();
        if let Some(old) = self.labels.take() {
            let mut l = vec![0; self.betas.len()];
            for (i, &new) in dmap.iter().enumerate() {
                if new != 0 {
                    l[new as usize] = old[i];
                }
            }
            self.labels = Some(l);
        }
        Compaction { darts: dmap, vertices: vmap }
    }
}
