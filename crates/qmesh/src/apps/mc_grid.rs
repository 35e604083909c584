//! A sampled scalar field as marching cubes reads it: points inside or outside as bits,
//! cells in layers along k, edges named by their lower point and axis.

use rayon::prelude::*;

/// The corners of a cell in hexahedron order (as [`crate::generate::hex_grid`]), as
/// offsets along (i, j, k).
pub(super) const CORNERS: [[usize; 3]; 8] =
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];

/// The field with its inside points as bits.
pub(super) struct Grid<'a> {
    pub values: &'a [f32],
    pub dims: [usize; 3],
    pub iso: f64,
    inside: Vec<u64>,
}

impl<'a> Grid<'a> {
    pub fn new(values: &'a [f32], dims: [usize; 3], iso: f64) -> Self {
        let inside = values
            .par_chunks(64)
            .map(|c| c.iter().enumerate().fold(0u64, |w, (b, &x)| w | (u64::from(f64::from(x) - iso <= 0.0) << b)))
            .collect();
        Grid { values, dims, iso, inside }
    }

    pub fn index(&self, [i, j, k]: [usize; 3]) -> usize {
        (i * self.dims[1] + j) * self.dims[2] + k
    }

    pub fn is_inside(&self, g: usize) -> bool {
        self.inside[g / 64] >> (g % 64) & 1 == 1
    }

    /// The corners of cell (i, j, k) in hexahedron order (as [`crate::generate::hex_grid`]).
    pub fn corners(&self, [i, j, k]: [usize; 3]) -> [usize; 8] {
        CORNERS.map(|[a, b, c]| self.index([i + a, j + b, k + c]))
    }

    /// The cells with corners on both sides, layer by layer (k), each layer in the
    /// order (j, then i) of the whole grid's cells, as `(j·(nx − 1) + i, configuration)`.
    /// Rows of cells along k are tested 64 at a time on the inside bits (the points
    /// along k are consecutive bits).
    pub fn crossed_layers(&self) -> Vec<Vec<(u32, u8)>> {
        let [nx, ny, nz] = self.dims;
        let cells_k = nz - 1;
        let row = |i: usize, j: usize| (i * ny + j) * nz;
        // Per j, the crossed cells in (i, k) order.
        let by_j: Vec<Vec<(u32, u32, u8)>> = (0..ny - 1)
            .into_par_iter()
            .map(|j| {
                let mut out = Vec::new();
                for i in 0..nx - 1 {
                    for k0 in (0..cells_k).step_by(64) {
                        let words = CORNERS.map(|[di, dj, dk]| self.bits_at(row(i + di, j + dj) + k0 + dk));
                        let all = words.iter().fold(u64::MAX, |w, x| w & x);
                        let any = words.iter().fold(0, |w, x| w | x);
                        let valid = if cells_k - k0 >= 64 { u64::MAX } else { (1 << (cells_k - k0)) - 1 };
                        let mut crossed = any & !all & valid;
                        while crossed != 0 {
                            let b = crossed.trailing_zeros();
                            crossed &= crossed - 1;
                            let configuration =
                                words.iter().enumerate().fold(0u8, |c, (n, w)| c | (((w >> b) & 1) as u8) << n);
                            out.push(((k0 + b as usize) as u32, (j * (nx - 1) + i) as u32, configuration));
                        }
                    }
                }
                out
            })
            .collect();
        let mut counts = vec![0usize; cells_k];
        for &(k, _, _) in by_j.iter().flatten() {
            counts[k as usize] += 1;
        }
        let mut layers: Vec<Vec<(u32, u8)>> = counts.iter().map(|&n| Vec::with_capacity(n)).collect();
        for &(k, cell, configuration) in by_j.iter().flatten() {
            layers[k as usize].push((cell, configuration));
        }
        layers
    }

    /// Inside bits `start..start + 64` (zeros past the grid).
    fn bits_at(&self, start: usize) -> u64 {
        let (w, o) = (start / 64, start % 64);
        let word = |w: usize| self.inside.get(w).copied().unwrap_or(0);
        if o == 0 { word(w) } else { (word(w) >> o) | (word(w + 1) << (64 - o)) }
    }

    /// The grid point of `g`'s coordinates.
    pub fn coordinates(&self, g: usize) -> [usize; 3] {
        let [_, ny, nz] = self.dims;
        [g / (ny * nz), g / nz % ny, g % nz]
    }

    /// The key of the grid edge between neighbouring points `a` and `b`: 3 × the lower
    /// point + the axis.
    pub fn edge_key(&self, a: usize, b: usize) -> u64 {
        let (lo, hi) = (a.min(b), a.max(b));
        let axis = match hi - lo {
            1 => 2,
            d if d == self.dims[2] => 1,
            _ => 0,
        };
        3 * lo as u64 + axis
    }

    /// The plane k = const holding edge `key`, if it lies in one (not along k).
    pub fn plane_of(&self, key: u64) -> Option<usize> {
        (key % 3 != 2).then(|| self.coordinates((key / 3) as usize)[2])
    }

    /// Where the surface crosses the edge from inside point `a` to outside point `b`.
    pub fn crossing(&self, a: usize, b: usize) -> [f64; 3] {
        let (va, vb) = (f64::from(self.values[a]), f64::from(self.values[b]));
        let t = if vb != va { ((self.iso - va) / (vb - va)).clamp(1e-6, 1.0 - 1e-6) } else { 0.5 };
        let (p, q) = (self.coordinates(a), self.coordinates(b));
        [0, 1, 2].map(|k| p[k] as f64 + t * (q[k] as f64 - p[k] as f64))
    }
}
