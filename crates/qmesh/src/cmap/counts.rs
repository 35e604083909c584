//! Cell counts, boundary, connected components and Euler characteristic.

use super::bitset::BitSet;
use super::dart::Dart;
use super::orbit::{Orbit, walk_orbit};
use super::validity::Violation;

/// Result of [`CMap3::census`].
#[derive(Clone, Debug, Default)]
pub struct Census {
    pub counts: CellCounts,
    /// As [`CMap3::is_valid`].
    pub violations: Vec<Violation>,
    /// One dart per volume.
    pub volume_reps: Vec<Dart>,
    /// One dart per 3-free half-face (the boundary of a volume map; every face of a
    /// surface map): the smallest of its cycle, in increasing order.
    pub boundary_reps: Vec<Dart>,
}

/// Result of [`CMap3::face_sweep`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FaceSweep {
    pub half_faces: usize,
    pub sewn_half_faces: usize,
}

impl FaceSweep {
    /// Faces of a valid map: two sewn half-faces make one face.
    pub fn faces(&self) -> usize {
        self.half_faces - self.sewn_half_faces / 2
    }
}
use super::storage::CMap3;

/// Number of cells of each dimension, as counted by [`CMap3::count_cells`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CellCounts {
    pub darts: usize,
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub volumes: usize,
    pub components: usize,
    /// 3-free faces (the boundary of a volume map).
    pub boundary_faces: usize,
}

impl CellCounts {
    /// V − E + F − C for volume maps, V − E + F for surface maps.
    pub fn euler_characteristic(&self, dimension: u8) -> i64 {
        let (v, e, f, c) = (self.vertices as i64, self.edges as i64, self.faces as i64, self.volumes as i64);
        if dimension == 3 { v - e + f - c } else { v - e + f }
    }
}

impl CMap3 {
    /// Counts vertices, edges, faces, volumes and connected components.
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, (i * i) as f64, (i * i * i) as f64])).collect();
    /// m.make_tetrahedron([v[0], v[1], v[2], v[3]]);
    /// let c = m.count_cells();
    /// assert_eq!((c.vertices, c.edges, c.faces, c.volumes), (4, 6, 4, 1));
    /// assert_eq!(m.euler_characteristic(), 1);
    /// ```
    pub fn count_cells(&self) -> CellCounts {
        self.census().counts
    }

    /// The census by its definition, on any map (valid or not): one orbit walk per
    /// cell dimension, run side by side. [`census`](Self::census) equals it and is
    /// faster on valid maps; this is its fallback and its reference in tests. Volume
    /// representatives are the darts each volume was entered by.
    pub fn census_reference(&self) -> Census {
        let (((vertices, shared), edges), ((sweep, (components, reps)), local)) = rayon::join(
            || rayon::join(|| self.vertex_census(), || self.cells(Orbit::Edge).count()),
            || {
                rayon::join(
                    || rayon::join(|| self.face_sweep(), || self.components_and_volumes()),
                    || self.local_violations_all(),
                )
            },
        );
        let boundary_faces = sweep.half_faces - sweep.sewn_half_faces;
        let counts = CellCounts {
            darts: self.nb_darts(),
            vertices,
            edges,
            faces: sweep.faces(),
            volumes: reps.len(),
            components,
            boundary_faces,
        };
        let violations = if local.is_empty() { shared } else { local };
        let boundary_reps = self
            .darts()
            .filter(|&d| self.is_free(d, 3) && self.orbit(d, Orbit::HalfFace).iter().all(|&x| x >= d))
            .collect();
        Census { counts, violations, volume_reps: reps, boundary_reps }
    }

    /// Half-faces (β1 cycles) and how many of them are 3-sewn, in one sequential sweep.
    pub fn face_sweep(&self) -> FaceSweep {
        let mut seen = BitSet::with_len(self.dart_capacity());
        let (mut half_faces, mut sewn) = (0, 0);
        for d in self.darts() {
            if seen.get(d.idx()) {
                continue;
            }
            half_faces += 1;
            sewn += usize::from(!self.is_free(d, 3));
            let mut x = d;
            while seen.insert(x.idx()) {
                match self.beta(x, 1) {
                    Some(n) => x = n,
                    None => break,
                }
            }
        }
        FaceSweep { half_faces, sewn_half_faces: sewn }
    }

    /// Euler characteristic (see [`CellCounts::euler_characteristic`]).
    pub fn euler_characteristic(&self) -> i64 {
        self.count_cells().euler_characteristic(self.dimension)
    }

    /// Faces lying on the boundary of a volume map (3-free faces).
    pub fn boundary_faces(&self) -> usize {
        let s = self.face_sweep();
        s.half_faces - s.sewn_half_faces
    }

    /// Boundary edges of a surface map (2-free darts).
    pub fn boundary_edges(&self) -> usize {
        self.darts().filter(|&d| self.is_free(d, 2)).count()
    }

    /// Number of connected components, walked volume by volume: each volume is
    /// finished (its darts are stored together) before crossing β3 to a neighbour, which
    /// is several times faster than a dart-level walk on large meshes.
    pub fn connected_components(&self) -> usize {
        self.components_and_volumes().0
    }

    /// Connected components and one dart per volume (the dart each volume was entered by).
    fn components_and_volumes(&self) -> (usize, Vec<Dart>) {
        let mut reps = Vec::new();
        let mut seen = BitSet::with_len(self.dart_capacity());
        let (mut entries, mut local) = (Vec::new(), Vec::new());
        let mut components = 0;
        for d in self.darts() {
            if seen.get(d.idx()) {
                continue;
            }
            components += 1;
            entries.push(d.raw());
            while let Some(e) = entries.pop() {
                let e = Dart::from_raw(e).expect("entries hold no ε");
                if seen.get(e.idx()) {
                    continue;
                }
                reps.push(e);
                walk_orbit(self, e, Orbit::Volume, &mut seen, &mut local, |x| {
                    let p = self.beta_raw(x.raw(), 3);
                    if p != 0 {
                        entries.push(p);
                    }
                });
            }
        }
        (components, reps)
    }
}
