//! The half-edges of a mesh's polygons grouped by origin vertex (compressed rows): which
//! corner runs u → v, in 8 bytes per corner and 4 per point, for checking and
//! triangulating large surfaces without a map or a hash table.

use super::indexed::IndexedMesh;

/// Half-edges by origin vertex. Corner `h` is position `h` of `mesh.poly_conn`; its
/// half-edge runs from its vertex to the next corner's.
#[derive(Debug)]
pub struct HalfEdges {
    /// The next corner of each corner in its polygon.
    next: Vec<u32>,
    /// Per vertex v, `corners[first[v]..first[v + 1]]` are the corners at v.
    first: Vec<u32>,
    corners: Vec<u32>,
    /// The polygons kept.
    pub polygons: usize,
}

impl HalfEdges {
    /// The half-edges of the polygons of `mesh` that `keep` accepts; None when a node is
    /// out of range.
    pub fn new(mesh: &IndexedMesh, keep: impl Fn(&[u32]) -> bool) -> Option<Self> {
        Self::of_polygons(&mesh.poly_offsets, &mesh.poly_conn, mesh.points.len(), keep)
    }

    /// [`HalfEdges::new`] on polygons given as offsets and nodes, on `n_points` points.
    pub fn of_polygons(
        offsets: &[usize],
        conn: &[u32],
        n_points: usize,
        keep: impl Fn(&[u32]) -> bool,
    ) -> Option<Self> {
        let mut next = vec![u32::MAX; conn.len()];
        let mut count = vec![0u32; n_points + 1];
        let mut polygons = 0;
        for w in offsets.windows(2) {
            let (s, e) = (w[0], w[1]);
            let p = &conn[s..e];
            if p.iter().any(|&v| v as usize >= n_points) {
                return None;
            }
            if !keep(p) {
                continue;
            }
            polygons += 1;
            for h in s..e {
                next[h] = if h + 1 < e { h + 1 } else { s } as u32;
                count[conn[h] as usize + 1] += 1;
            }
        }
        for v in 0..n_points {
            count[v + 1] += count[v];
        }
        let first = count;
        let mut fill = first.clone();
        let mut corners = vec![0u32; first[n_points] as usize];
        for (h, &n) in next.iter().enumerate() {
            if n != u32::MAX {
                let slot = &mut fill[conn[h] as usize];
                corners[*slot as usize] = h as u32;
                *slot += 1;
            }
        }
        Some(HalfEdges { next, first, corners, polygons })
    }

    /// The next corner of `h` in its polygon.
    pub fn next(&self, h: u32) -> u32 {
        self.next[h as usize]
    }

    /// The corners at vertex `v`.
    pub fn at(&self, v: u32) -> &[u32] {
        &self.corners[self.first[v as usize] as usize..self.first[v as usize + 1] as usize]
    }

    /// The corner whose half-edge runs `u → v`, if any (the first one).
    pub fn find(&self, conn: &[u32], u: u32, v: u32) -> Option<u32> {
        self.at(u).iter().copied().find(|&h| conn[self.next(h) as usize] == v)
    }
}
