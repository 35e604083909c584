//! Every subdivision of a hexahedron into tetrahedra on its 8 corners (Pellerin,
//! Verhetsel & Remacle 2018, used by 2025 §7.1): for each of the 2⁶ choices of one
//! diagonal per quad face, a depth-first search over sets of corner tetrahedra that
//! fill the hexahedron as a triangulated 3-ball whose boundary is exactly the 12
//! chosen triangles.
//!
//! Corners are bit sets (bit k = coordinate k of the unit cube, [`super::super::cube`]);
//! a triangle or a tetrahedron is the `u8` mask of its corners. The search is purely
//! combinatorial: whether a subdivision can be realised with positive tetrahedra is
//! decided separately ([`super::realize`]).

use rustc_hash::FxHashSet;

use crate::apps::cube;

/// A subdivision: its tetrahedra as corner masks, sorted (a canonical key).
pub(crate) type Subdivision = Vec<u8>;

/// What a triangle may be part of, given the face diagonals.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    /// One of the 12 boundary triangles: in exactly one tetrahedron.
    Boundary,
    /// Any other triangle: in none or two tetrahedra. This includes the two triangles of
    /// a face through its other diagonal: when the face is folded along the chosen
    /// diagonal, that one passes inside (the 15-tetrahedron subdivisions use all six).
    Inner,
}

/// The four corners of each face.
fn face_masks() -> [u8; 6] {
    cube::faces().map(|f| f.iter().fold(0u8, |m, &c| m | 1 << c))
}

/// The two boundary triangles of face `f` when its diagonal is the one through its
/// corners 0 and 2 (`choice` false) or 1 and 3 (`choice` true), in outward order.
pub(crate) fn face_triangles(f: usize, choice: bool) -> [[u8; 3]; 2] {
    let c = cube::faces()[f];
    if choice { [[c[1], c[2], c[3]], [c[1], c[3], c[0]]] } else { [[c[0], c[1], c[2]], [c[0], c[2], c[3]]] }
}

/// The 12 boundary triangles (outward) of a diagonal choice (bit f for face f).
pub(crate) fn boundary_triangles(diagonals: u8) -> Vec<[u8; 3]> {
    (0..6).flat_map(|f| face_triangles(f, diagonals >> f & 1 == 1)).collect()
}

fn mask(t: &[u8]) -> u8 {
    t.iter().fold(0u8, |m, &c| m | 1 << c)
}

/// The triangles of a tetrahedron mask.
fn triangles_of(tet: u8) -> [u8; 4] {
    let mut out = [0u8; 4];
    let mut k = 0;
    for c in 0..8 {
        if tet >> c & 1 == 1 {
            out[k] = tet & !(1 << c);
            k += 1;
        }
    }
    out
}

/// The parity of the corner order (x, y, z) against increasing order.
fn parity(t: [u8; 3]) -> u8 {
    u8::from(t[0] > t[1]) ^ u8::from(t[0] > t[2]) ^ u8::from(t[1] > t[2])
}

/// The corners of a triangle mask in the order of parity `p`.
fn ordered(t: u8, p: u8) -> [u8; 3] {
    let mut c = [0u8; 3];
    let mut k = 0;
    for x in 0..8 {
        if t >> x & 1 == 1 {
            c[k] = x;
            k += 1;
        }
    }
    if p == 1 {
        c.swap(1, 2);
    }
    c
}

/// Outward faces of a positively ordered tetrahedron (p0, p1, p2, p3).
fn outward_faces(p: [u8; 4]) -> [[u8; 3]; 4] {
    [[p[0], p[2], p[1]], [p[0], p[1], p[3]], [p[1], p[2], p[3]], [p[0], p[3], p[2]]]
}

/// The search state. Tetrahedra are added on an open triangle, on the side it still
/// misses, so the complex stays oriented: `need[t]` is the parity a tetrahedron added
/// on `t` must give `t` as its outward face (boundary triangles face out of the
/// hexahedron; an inner triangle with one tetrahedron faces the other way for the next).
struct Search {
    role: [Role; 256],
    count: [u8; 256],
    need: [u8; 256],
    tets: Vec<u8>,
    faces: [u8; 6],
    found: FxHashSet<Subdivision>,
}

impl Search {
    fn new(diagonals: u8) -> Search {
        let faces = face_masks();
        let mut role = [Role::Inner; 256];
        let mut need = [0u8; 256];
        for t in boundary_triangles(diagonals) {
            role[mask(&t) as usize] = Role::Boundary;
            need[mask(&t) as usize] = parity(t);
        }
        Search { role, count: [0; 256], need, tets: Vec::new(), faces, found: FxHashSet::default() }
    }

    fn is_open(&self, t: u8) -> bool {
        match self.role[t as usize] {
            Role::Boundary => self.count[t as usize] == 0,
            Role::Inner => self.count[t as usize] == 1,
        }
    }

    /// The positively ordered tetrahedron on open triangle `t` and corner `c`, if it
    /// fits: not flat on a face, not there yet, and every face either free with the
    /// right orientation or the missing side of an open triangle.
    ///
    /// A tetrahedron on the four corners of a face would be flat on the unit hexahedron
    /// and hold both of the face's diagonals: not part of a subdivision.
    fn candidate(&self, t: u8, c: u8) -> Option<[u8; 4]> {
        let tet = t | 1 << c;
        if t >> c & 1 == 1 || self.faces.contains(&tet) || self.tets.contains(&tet) {
            return None;
        }
        let [x, y, z] = ordered(t, self.need[t as usize]);
        let p = [x, z, y, c];
        if self.closes_an_edge(tet) {
            return None;
        }
        outward_faces(p)
            .iter()
            .all(|&f| {
                let m = mask(&f) as usize;
                match (self.role[m], self.count[m]) {
                    (Role::Boundary, 0) | (Role::Inner, 1) => parity(f) == self.need[m],
                    (Role::Inner, 0) => true,
                    _ => false,
                }
            })
            .then_some(p)
    }

    /// Whether an edge of `tet` already has tetrahedra all around it (every triangle
    /// on it in two): another one there would make the edge non-manifold.
    fn closes_an_edge(&self, tet: u8) -> bool {
        let corners = ordered(tet & !(1 << (7 - tet.leading_zeros() as u8)), 0);
        let last = 7 - tet.leading_zeros() as u8;
        let all = [corners[0], corners[1], corners[2], last];
        (0..4).any(|i| {
            (i + 1..4).any(|j| {
                let e = 1u8 << all[i] | 1 << all[j];
                let mut any = false;
                for x in 0..8 {
                    if e >> x & 1 == 0 {
                        match self.count[(e | 1 << x) as usize] {
                            0 => {}
                            2 => any = true,
                            _ => return false,
                        }
                    }
                }
                any
            })
        })
    }

    fn run(&mut self) {
        // The open triangle with the fewest candidates (a dead end as soon as one has none).
        let mut best: Option<(usize, u8)> = None;
        for t in 0..=255u8 {
            if t.count_ones() != 3 || !self.is_open(t) {
                continue;
            }
            let n = (0..8).filter(|&c| self.candidate(t, c).is_some()).count();
            if best.is_none_or(|b| n < b.0) {
                best = Some((n, t));
                if n <= 1 {
                    break;
                }
            }
        }
        let Some((_, open)) = best else {
            if is_ball(&self.tets) {
                let mut key = self.tets.clone();
                key.sort_unstable();
                self.found.insert(key);
            }
            return;
        };
        for c in 0..8 {
            let Some(p) = self.candidate(open, c) else { continue };
            let tet = open | 1 << c;
            for f in outward_faces(p) {
                let m = mask(&f) as usize;
                self.count[m] += 1;
                if self.role[m] == Role::Inner && self.count[m] == 1 {
                    self.need[m] = parity(f) ^ 1;
                }
            }
            self.tets.push(tet);
            self.run();
            self.tets.pop();
            triangles_of(tet).iter().for_each(|&t| self.count[t as usize] -= 1);
        }
    }
}

/// Whether tetrahedra whose triangles are each in at most two of them (boundary ones in
/// one) form a 3-manifold: every corner's link is a disk (connected, Euler
/// characteristic 1). All corners lie on the boundary, and a 3-manifold bounded by the
/// 12 triangles with 8 vertices is a ball.
fn is_ball(tets: &[u8]) -> bool {
    (0..8).all(|v| {
        let link: Vec<u8> = tets.iter().filter(|&&t| t >> v & 1 == 1).map(|&t| t & !(1 << v)).collect();
        if link.is_empty() {
            return false;
        }
        let vertices = link.iter().fold(0u8, |m, &t| m | t).count_ones() as i32;
        let mut edges = FxHashSet::default();
        for &t in &link {
            for c in 0..8 {
                if t >> c & 1 == 1 {
                    edges.insert(t & !(1 << c));
                }
            }
        }
        let chi = vertices - edges.len() as i32 + link.len() as i32;
        chi == 1 && connected(&link)
    })
}

/// Whether triangles are connected through shared edges.
fn connected(tris: &[u8]) -> bool {
    let mut reached = vec![false; tris.len()];
    let mut stack = vec![0];
    reached[0] = true;
    while let Some(i) = stack.pop() {
        for j in 0..tris.len() {
            if !reached[j] && (tris[i] & tris[j]).count_ones() == 2 {
                reached[j] = true;
                stack.push(j);
            }
        }
    }
    reached.iter().all(|&r| r)
}

/// The diagonal choice (bits as in [`boundary_triangles`]) that the corner
/// permutation `p` makes of `diagonals`.
fn map_diagonals(diagonals: u8, p: &[u8; 8]) -> u8 {
    let faces = cube::faces();
    let mut out = 0u8;
    for f in 0..6 {
        let c = faces[f];
        let (a, b) = if diagonals >> f & 1 == 1 { (c[1], c[3]) } else { (c[0], c[2]) };
        let image = 1u8 << p[a as usize] | 1 << p[b as usize];
        for (g, d) in faces.iter().enumerate() {
            if image == 1 << d[1] | 1 << d[3] {
                out |= 1 << g;
            }
        }
    }
    out
}

/// Every subdivision of the cube's corners for every diagonal choice, with the choice
/// (bit f = face f's diagonal through its corners 1 and 3), sorted. The search runs
/// once per diagonal choice up to the cube's symmetries; the other choices get the
/// images of its subdivisions.
pub(crate) fn all_subdivisions() -> Vec<(u8, Subdivision)> {
    use rayon::prelude::*;
    let symmetries = cube::symmetries();
    let mut found: Vec<FxHashSet<Subdivision>> = vec![FxHashSet::default(); 64];
    let representatives: Vec<u8> = (0..64u8).filter(|&d| symmetries.iter().all(|p| map_diagonals(d, p) >= d)).collect();
    let searched: Vec<(u8, FxHashSet<Subdivision>)> = representatives
        .into_par_iter()
        .map(|d| {
            let mut s = Search::new(d);
            s.run();
            (d, s.found)
        })
        .collect();
    for (diagonals, sub) in searched {
        for p in &symmetries {
            let d = map_diagonals(diagonals, p);
            for t in &sub {
                let mut image: Subdivision =
                    t.iter().map(|&m| (0..8).filter(|&c| m >> c & 1 == 1).fold(0u8, |r, c| r | 1 << p[c])).collect();
                image.sort_unstable();
                found[d as usize].insert(image);
            }
        }
    }
    let mut out = Vec::new();
    for (diagonals, set) in found.into_iter().enumerate() {
        let mut v: Vec<Subdivision> = set.into_iter().collect();
        v.sort();
        out.extend(v.into_iter().map(|t| (diagonals as u8, t)));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn five_and_six_tetrahedra_splits_are_found() {
        let all = all_subdivisions();
        let corners = |m: u8| (0..8u8).filter(move |&c| m >> c & 1 == 1);
        let one_parity = |m: u8| {
            let p: Vec<u32> = corners(m).map(|c| c.count_ones() % 2).collect();
            p.iter().all(|&x| x == p[0])
        };
        // The 5-tet splits: a central tetrahedron on corners of one parity.
        let five: Vec<_> = all.iter().filter(|(_, t)| t.len() == 5).collect();
        assert_eq!(five.len(), 2, "one per parity class of corners");
        for (_, t) in &five {
            assert_eq!(t.iter().filter(|&&m| one_parity(m)).count(), 1);
        }
        assert!(all.iter().all(|(_, t)| (5..=15).contains(&t.len())));
        // A subdivision has T - 5 inner edges (Euler), so 15 tets use every edge of K8.
        assert!(all.iter().any(|(_, t)| t.len() == 15));
    }
}
