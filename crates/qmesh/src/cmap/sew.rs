//! `sew`/`unsew` with whole-orbit consistency (as CGAL's `sew<i>`), 2022 §2.2.
//!
//! Sewing keeps β1∘β3 an involution: 1-sewing also links the β3 images, 3-sewing
//! pairs two whole faces in opposite directions. Vertex ids follow: orbits that merge
//! take one id, orbits that an unsew splits get a fresh id (a copy of the position).

use super::dart::Dart;
use super::error::MapError;
use super::orbit::{Orbit, OrbitWalker};
use super::storage::CMap3;
use rayon::prelude::*;
use rustc_hash::FxHashSet;

impl CMap3 {
    /// Gives every dart of the vertex orbit of `d` the vertex id of `d`.
    pub(crate) fn harmonize_vertex(&mut self, d: Dart) {
        let v = self.vertex_of(d);
        self.with_scratch(|m, w| {
            for &x in w.collect(m, d, Orbit::Vertex) {
                m.vertex[x.idx()] = v;
            }
        });
    }

    /// After an unsew or a removal: vertex orbits through `touched` that now share an id
    /// with another orbit get a fresh id at the same position. Of the orbits sharing an
    /// id, the one met first in `touched` keeps it; the others get fresh ids in the
    /// order they are met. Ids are independent, so many are checked on all cores.
    pub(crate) fn split_vertex_ids(&mut self, touched: &[Dart]) {
        let mut by_id: Vec<(u32, u32)> = touched
            .par_iter()
            .with_min_len(1 << 12)
            .enumerate()
            .filter(|&(_, &t)| self.is_live(t))
            .map(|(i, &t)| (self.vertex_of(t), i as u32))
            .collect();
        by_id.par_sort_unstable();
        let groups: Vec<&[(u32, u32)]> = by_id.chunk_by(|a, b| a.0 == b.0).filter(|g| g.len() > 1).collect();
        let map = &*self;
        // Each touched dart's step along the boundary around its origin, all read at
        // once on all cores: the steps' memory reads overlap, where the walks below,
        // step after step, would wait for each one.
        let steps: Vec<FanStep> = touched
            .par_iter()
            .with_min_len(1 << 10)
            .map(|&t| if map.is_live(t) { map.fan_step(t.raw()) } else { FanStep::NONE })
            .collect();
        // The orbits after the first of one id, each with where it was first met. Most
        // ids have one orbit: the others are looked for only among the darts outside it.
        let split_off = |w: &mut OrbitWalker, group: &[(u32, u32)]| {
            let first = touched[group[0].1 as usize];
            let mut out: Vec<(u32, Vec<Dart>)> = Vec::new();
            if map.boundary_fan_reaches(first, group.iter().map(|g| (touched[g.1 as usize], steps[g.1 as usize]))) {
                return out;
            }
            w.collect(map, first, Orbit::Vertex);
            let others: Vec<u32> =
                group[1..].iter().map(|g| g.1).filter(|&at| !w.contains(touched[at as usize])).collect();
            if others.is_empty() {
                return out;
            }
            let mut reached: FxHashSet<Dart> = w.collect(map, first, Orbit::Vertex).iter().copied().collect();
            for at in others {
                let t = touched[at as usize];
                if !reached.contains(&t) {
                    let orbit = w.collect(map, t, Orbit::Vertex);
                    reached.extend(orbit.iter().copied());
                    out.push((at, orbit.to_vec()));
                }
            }
            out
        };
        let mut apart: Vec<(u32, Vec<Dart>)> = if groups.len() < 64 {
            let mut w = OrbitWalker::new();
            groups.iter().flat_map(|g| split_off(&mut w, g)).collect()
        } else {
            groups.par_iter().map_init(OrbitWalker::new, |w, g| split_off(w, g)).flatten_iter().collect()
        };
        apart.sort_unstable_by_key(|(at, _)| *at);
        for (_, orbit) in apart {
            let fresh = self.add_vertex(self.position(self.vertex_of(orbit[0])));
            for x in orbit {
                self.vertex[x.idx()] = fresh;
            }
        }
    }

    /// Whether walking around the origin of `first`, a 3-free dart, along the
    /// boundary faces there reaches every dart of `darts` (3-free darts with the same
    /// origin, each with its [`fan_step`](Self::fan_step)). Each step turns around an
    /// edge through the volumes still there, so what it reaches is in the vertex orbit
    /// of `first`: a cheap proof that a vertex did not come apart (a vertex whose
    /// boundary is not one fan, or a map with 2-free darts, gets `false`, and the caller
    /// walks the whole orbit).
    fn boundary_fan_reaches(&self, first: Dart, darts: impl Iterator<Item = (Dart, FanStep)>) -> bool {
        let start = first.raw();
        if self.beta_raw(start, 3) != 0 {
            return false;
        }
        let known: smallvec::SmallVec<[(u32, FanStep); 16]> = darts.map(|(d, s)| (d.raw(), s)).collect();
        let mut wanted: smallvec::SmallVec<[u32; 16]> = known.iter().map(|k| k.0).filter(|&x| x != start).collect();
        let (mut x, mut steps) = (start, 0);
        while !wanted.is_empty() {
            // The previous dart ends at the vertex; turn around its edge to the next face
            // that no volume is 3-sewn to (a step read already, or read now).
            let step = known.iter().find(|k| k.0 == x).map_or_else(|| self.fan_step(x), |k| k.1);
            steps += step.hops as usize;
            if step.to == 0 || step.to == start || steps >= FanStep::MAX_HOPS as usize {
                return false;
            }
            wanted.retain(|&mut y| y != step.to);
            x = step.to;
        }
        true
    }

    /// From the 3-free dart `x`, the next 3-free dart with the same origin around it:
    /// turn around the edge that ends there, through the volumes 3-sewn there.
    fn fan_step(&self, x: u32) -> FanStep {
        let b = |x: u32, i: usize| self.beta_raw(x, i);
        let mut to = b(b(x, 0), 2);
        let mut hops = 1;
        while to != 0 && b(to, 3) != 0 && hops < FanStep::MAX_HOPS {
            to = b(b(to, 3), 2);
            hops += 1;
        }
        FanStep { to: if hops < FanStep::MAX_HOPS { to } else { 0 }, hops }
    }

    fn not_sewable(i: usize, d1: Dart, d2: Dart, why: &'static str) -> MapError {
        MapError::NotSewable { i, d1, d2, why }
    }

    /// 1-sews `d1` to `d2` (β1(d1) = d2); when both are 3-sewn, also β1(β3(d2)) = β3(d1).
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// m.set_dimension(2);
    /// let v: Vec<u32> = (0..3).map(|i| m.add_vertex([i as f64, (i % 2) as f64, 0.0])).collect();
    /// let d = m.make_polygon(&v);
    /// let n = m.next(d);
    /// m.unsew1(d).unwrap(); // open the triangle …
    /// assert!(m.is_free(d, 1) && !m.is_valid().is_empty());
    /// m.sew1(d, n).unwrap(); // … and close it again
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Errors
    /// If β1(d1) or β0(d2) is already sewn, or only one of the two is 3-sewn.
    pub fn sew1(&mut self, d1: Dart, d2: Dart) -> Result<(), MapError> {
        self.err_if_dead(d1)?;
        self.err_if_dead(d2)?;
        if !self.is_free(d1, 1) || !self.is_free(d2, 0) {
            return Err(Self::not_sewable(1, d1, d2, "β1(d1) or β0(d2) is not free"));
        }
        let (e1, e2) = (self.beta(d1, 3), self.beta(d2, 3));
        match (e1, e2) {
            (None, None) => {}
            (Some(e1), Some(e2)) if self.is_free(e2, 1) && self.is_free(e1, 0) => {}
            _ => {
                return Err(Self::not_sewable(1, d1, d2, "their β3 images cannot be 1-sewn in turn"));
            }
        }
        self.link(d1, 1, d2);
        if let (Some(e1), Some(e2)) = (e1, e2) {
            self.link(e2, 1, e1);
            self.harmonize_vertex(e1);
        }
        self.harmonize_vertex(d2);
        Ok(())
    }

    /// 2-sews `d1` and `d2` (two darts of the same edge in opposite directions).
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// m.set_dimension(2);
    /// let v: Vec<u32> = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]].iter().map(|p| m.add_vertex(*p)).collect();
    /// let a = m.make_polygon(&[v[0], v[1], v[2]]); // a: 0→1
    /// let b = m.make_polygon(&[v[0], v[2], v[3]]); // b: 0→2
    /// let ab = m.prev(a); // 2→0
    /// m.sew2(ab, b).unwrap();
    /// assert!(m.is_valid().is_empty());
    /// assert_eq!(m.boundary_edges(), 4);
    /// m.unsew2(b).unwrap();
    /// assert_eq!(m.boundary_edges(), 6);
    /// ```
    ///
    /// # Errors
    /// If either is already 2-sewn or `d1 == d2`.
    pub fn sew2(&mut self, d1: Dart, d2: Dart) -> Result<(), MapError> {
        self.err_if_dead(d1)?;
        self.err_if_dead(d2)?;
        if d1 == d2 || !self.is_free(d1, 2) || !self.is_free(d2, 2) {
            return Err(Self::not_sewable(2, d1, d2, "both darts must be distinct and 2-free"));
        }
        self.link(d1, 2, d2);
        self.harmonize_vertex(d1);
        self.harmonize_vertex(d2);
        Ok(())
    }

    /// 3-sews the face of `d1` with the face of `d2`: d1 ↔ d2, β1(d1) ↔ β0(d2), …
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// let p = |m: &mut CMap3, x: f64, y: f64, z: f64| m.add_vertex([x, y, z]);
    /// let (a, b, c, t, u) = (p(&mut m, 0., 0., 0.), p(&mut m, 1., 0., 0.), p(&mut m, 0., 1., 0.), p(&mut m, 0., 0., 1.), p(&mut m, 0., 0., -1.));
    /// let d1 = m.make_tetrahedron([a, b, c, t]); // face a-b-c, seen from t
    /// let d2 = m.make_tetrahedron([a, c, b, u]); // face a-c-b, seen from u
    /// // d1 runs a→b, so its partner runs b→a: the dart before a in the second tet's face.
    /// let d2 = m.prev(d2);
    /// assert!(m.is_sewable3(d1, d2));
    /// m.sew3(d1, d2).unwrap();
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Errors
    /// If the faces have different lengths, are the same face, or any dart is 3-sewn.
    pub fn sew3(&mut self, d1: Dart, d2: Dart) -> Result<(), MapError> {
        self.err_if_dead(d1)?;
        self.err_if_dead(d2)?;
        if !self.is_sewable3(d1, d2) {
            return Err(Self::not_sewable(3, d1, d2, "faces must be distinct, 3-free and of equal length"));
        }
        self.link_faces3(d1, d2);
        let mut x = d1;
        loop {
            self.harmonize_vertex(x);
            x = self.next(x);
            if x == d1 {
                break;
            }
        }
        Ok(())
    }

    /// Low-level 3-link of two whole faces (d1 ↔ d2, β1(d1) ↔ β0(d2), …) without checks
    /// or vertex-id updates, for builders that already share vertex ids.
    pub fn link_faces3(&mut self, d1: Dart, d2: Dart) {
        let (mut x, mut y) = (d1, d2);
        loop {
            self.link(x, 3, y);
            x = self.next(x);
            y = self.prev(y);
            if x == d1 {
                break;
            }
        }
    }

    /// Whether [`sew3`](Self::sew3) would accept `d1`, `d2`.
    pub fn is_sewable3(&self, d1: Dart, d2: Dart) -> bool {
        let (mut x, mut y) = (d1, d2);
        loop {
            if !self.is_free(x, 3) || !self.is_free(y, 3) || y == d1 {
                return false;
            }
            x = self.next(x);
            y = self.prev(y);
            if (x == d1) != (y == d2) {
                return false;
            }
            if x == d1 {
                return true;
            }
        }
    }

    /// 1-unsews `d` from β1(d) (and β3 images accordingly).
    ///
    /// # Errors
    /// If d is 1-free.
    pub fn unsew1(&mut self, d: Dart) -> Result<(), MapError> {
        self.err_if_dead(d)?;
        let n = self.beta(d, 1).ok_or(MapError::AlreadyFree(d, 1))?;
        let mut touched = vec![d, n];
        if let (Some(e1), Some(e2)) = (self.beta(d, 3), self.beta(n, 3)) {
            self.unlink(e2, 1);
            touched.extend([e1, e2]);
        }
        self.unlink(d, 1);
        touched.extend(touched.clone().into_iter().filter_map(|t| self.beta(t, 2)));
        self.split_vertex_ids(&touched);
        Ok(())
    }

    /// 2-unsews `d` and β2(d).
    ///
    /// # Errors
    /// If d is 2-free.
    pub fn unsew2(&mut self, d: Dart) -> Result<(), MapError> {
        self.err_if_dead(d)?;
        let o = self.beta(d, 2).ok_or(MapError::AlreadyFree(d, 2))?;
        self.unlink(d, 2);
        let touched: Vec<Dart> = [Some(d), Some(o), self.beta(d, 1), self.beta(o, 1)].into_iter().flatten().collect();
        self.split_vertex_ids(&touched);
        Ok(())
    }

    /// 3-unsews the whole face of `d` from its neighbour volume. Vertices that were only
    /// joined through that face become distinct vertices again.
    ///
    /// ```
    /// use qmesh::cmap::CMap3;
    /// let mut m = CMap3::new();
    /// let p = |m: &mut CMap3, x: f64, y: f64, z: f64| m.add_vertex([x, y, z]);
    /// let (a, b, c, t, u) = (p(&mut m, 0., 0., 0.), p(&mut m, 1., 0., 0.), p(&mut m, 0., 1., 0.), p(&mut m, 0., 0., 1.), p(&mut m, 0., 0., -1.));
    /// let d1 = m.make_tetrahedron([a, b, c, t]);
    /// let d2 = m.make_tetrahedron([a, c, b, u]);
    /// let d2 = m.prev(d2);
    /// m.sew3(d1, d2).unwrap();
    /// assert_eq!(m.count_cells().vertices, 5);
    /// m.unsew3(d1).unwrap();
    /// assert_eq!(m.count_cells().vertices, 8);
    /// assert!(m.is_valid().is_empty());
    /// ```
    ///
    /// # Errors
    /// If d is 3-free.
    pub fn unsew3(&mut self, d: Dart) -> Result<(), MapError> {
        self.err_if_dead(d)?;
        if self.is_free(d, 3) {
            return Err(MapError::AlreadyFree(d, 3));
        }
        let mut touched = Vec::new();
        let mut x = d;
        loop {
            if let Some(y) = self.beta(x, 3) {
                touched.extend([x, y]);
                self.unlink(x, 3);
            }
            x = self.next(x);
            if x == d {
                break;
            }
        }
        self.split_vertex_ids(&touched);
        Ok(())
    }
}

/// One step of a walk around a vertex along the boundary ([`CMap3::fan_step`]).
#[derive(Clone, Copy)]
struct FanStep {
    /// The next 3-free dart (0: none, or too far).
    to: u32,
    /// The edges turned around on the way (each a read or two).
    hops: u32,
}

impl FanStep {
    const NONE: FanStep = FanStep { to: 0, hops: 0 };
    /// Hops after which a walk is given up (far more than around a vertex of a mesh).
    const MAX_HOPS: u32 = 1 << 12;
}
