//! The unit cube's combinatorics shared by the generated pattern sets: corners as bit
//! sets, its 12 edges, its 6 outward faces and its 24 rotations.

/// Corner `c` of the unit cube: bit k of c is coordinate k.
pub(crate) fn corner(c: u8) -> [f64; 3] {
    [0, 1, 2].map(|k| f64::from(c >> k & 1))
}

/// The 12 edges as corner pairs.
pub(crate) fn edges() -> Vec<(u8, u8)> {
    let mut v = Vec::with_capacity(12);
    for a in 0..8u8 {
        for k in 0..3 {
            if a >> k & 1 == 0 {
                v.push((a, a | 1 << k));
            }
        }
    }
    v
}

/// The 6 faces as outward corner cycles: face 2k + s lies on coordinate k = s.
pub(crate) fn faces() -> [[u8; 4]; 6] {
    let mut out = [[0u8; 4]; 6];
    for k in 0..3 {
        let (u, v) = (1u8 << ((k + 1) % 3), 1u8 << ((k + 2) % 3));
        let lo = [0, u, u | v, v];
        out[2 * k] = [lo[0], lo[3], lo[2], lo[1]];
        out[2 * k + 1] = lo.map(|c| c | 1 << k);
    }
    out
}

pub(crate) fn edge_index(a: u8, b: u8) -> usize {
    let (a, b) = (a.min(b), a.max(b));
    edges().iter().position(|&e| e == (a, b)).expect("cube edge")
}

/// Split edges implied by refined faces.
pub(crate) fn edges_of_faces(refined: u8) -> u16 {
    let fs = faces();
    (0..6)
        .filter(|f| refined >> f & 1 == 1)
        .fold(0, |m, f| (0..4).fold(m, |m, i| m | 1 << edge_index(fs[f][i], fs[f][(i + 1) % 4])))
}

/// The 24 rotations of the cube as permutations of its corners.
pub(crate) fn rotations() -> Vec<[u8; 8]> {
    let perms = [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]];
    let mut out = Vec::new();
    for (pi, p) in perms.iter().enumerate() {
        for flips in 0..8u8 {
            // Even permutations need an even number of flips, odd ones an odd number.
            if (pi >= 3) != (flips.count_ones() % 2 == 1) {
                continue;
            }
            out.push(std::array::from_fn(|c| {
                let c = c as u8;
                (0..3).fold(0u8, |r, k| r | ((c >> p[k] & 1) ^ (flips >> k & 1)) << k)
            }));
        }
    }
    out
}

/// The 48 symmetries of the cube (the 24 rotations, then each composed with the
/// mirror x → 1 − x) as permutations of its corners.
pub(crate) fn symmetries() -> Vec<[u8; 8]> {
    let r = rotations();
    let mirrored = r.iter().map(|p| std::array::from_fn(|c| p[c ^ 1]));
    r.iter().copied().chain(mirrored.collect::<Vec<_>>()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotations_form_the_cube_group() {
        let r = rotations();
        assert_eq!(r.len(), 24);
        let set: std::collections::BTreeSet<[u8; 8]> = r.iter().copied().collect();
        assert_eq!(set.len(), 24);
        // Each keeps edges as edges.
        for p in &r {
            for (a, b) in edges() {
                assert_eq!((p[a as usize] ^ p[b as usize]).count_ones(), 1);
            }
        }
    }

    #[test]
    fn symmetries_are_48_distinct_cube_automorphisms() {
        let s = symmetries();
        let set: std::collections::BTreeSet<[u8; 8]> = s.iter().copied().collect();
        assert_eq!(set.len(), 48);
        for p in &s {
            for (a, b) in edges() {
                assert_eq!((p[a as usize] ^ p[b as usize]).count_ones(), 1);
            }
        }
    }

    #[test]
    fn faces_are_outward() {
        for (f, cyc) in faces().iter().enumerate() {
            let p = cyc.map(corner);
            let n = crate::geom::cross(crate::geom::sub(p[1], p[0]), crate::geom::sub(p[3], p[0]));
            let k = f / 2;
            let outward = if f % 2 == 1 { 1.0 } else { -1.0 };
            assert_eq!(n[k], outward, "face {f}");
        }
    }
}
