//! A map's tables as plain arrays, to store a map in a file and read it back (compiled
//! pattern sets). Reading checks everything a file could get wrong, so that a damaged
//! file gives an error, never a map that breaks an operation later.

use serde::{Deserialize, Serialize};

use super::storage::{CMap3, DEAD};

/// The stored form of a [`CMap3`]: per raw dart its links, vertex id and mark bits,
/// and per vertex id its position.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct MapTables {
    dimension: u8,
    pub(crate) betas: Vec<[u32; 4]>,
    vertex: Vec<u32>,
    marks: Vec<u32>,
    used_marks: u32,
    positions: Vec<[f64; 3]>,
    labels: Option<Vec<i32>>,
    uniform_label: Option<i32>,
}

impl CMap3 {
    /// This map's tables (deleted darts included, as they are).
    pub fn to_tables(&self) -> MapTables {
        MapTables {
            dimension: self.dimension,
            betas: self.betas.clone(),
            vertex: self.vertex.clone(),
            marks: self.marks.clone(),
            used_marks: self.used_marks,
            positions: self.positions.clone(),
            labels: self.labels.clone(),
            uniform_label: self.uniform_label,
        }
    }

    /// The map stored in `t`.
    ///
    /// # Errors
    /// What makes the tables no valid map, in words: tables of different lengths, a
    /// link or vertex id out of range, a link to a deleted dart, or a violation of
    /// [`CMap3::is_valid`].
    pub fn from_tables(t: MapTables) -> Result<CMap3, String> {
        let n = t.betas.len();
        if !(t.dimension == 2 || t.dimension == 3) {
            return Err(format!("dimension {} (2 or 3 expected)", t.dimension));
        }
        if n == 0 || t.vertex.len() != n || !(t.marks.is_empty() || t.marks.len() == n) {
            return Err(format!("{n} dart links for {} vertex ids and {} marks", t.vertex.len(), t.marks.len()));
        }
        if t.labels.as_ref().is_some_and(|l| l.len() != n) {
            return Err("one label per dart expected".into());
        }
        if t.betas[0] != [0; 4] || t.vertex[0] != DEAD {
            return Err("raw dart 0 is the null dart and must stay empty".into());
        }
        let live = |d: u32| (d as usize) < n && t.vertex[d as usize] != DEAD;
        let mut free_darts = Vec::new();
        for (d, (links, &v)) in t.betas.iter().zip(&t.vertex).enumerate().skip(1) {
            if v == DEAD {
                free_darts.push(d as u32);
            } else if v as usize >= t.positions.len() {
                return Err(format!("dart {d} has vertex id {v}, beyond the {} positions", t.positions.len()));
            } else if let Some(&b) = links.iter().find(|&&b| b != 0 && !live(b)) {
                return Err(format!("dart {d} links to {b}, which is no live dart"));
            }
        }
        let map = CMap3 {
            betas: t.betas,
            live: n - 1 - free_darts.len(),
            vertex: t.vertex,
            marks: t.marks,
            positions: t.positions,
            free_darts,
            used_marks: t.used_marks,
            dimension: t.dimension,
            scratch: Default::default(),
            labels: t.labels,
            uniform_label: t.uniform_label,
        };
        match map.is_valid().first() {
            Some(v) => Err(format!("not a valid map: {v}")),
            None => Ok(map),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetrahedron() -> CMap3 {
        let mut m = CMap3::new();
        let v: Vec<u32> = (0..4).map(|i| m.add_vertex([i as f64, (i * i) as f64, (i * i * i) as f64])).collect();
        let d = m.make_tetrahedron([v[0], v[1], v[2], v[3]]);
        let mark = m.reserve_mark().unwrap();
        m.mark(d, mark);
        m
    }

    #[test]
    fn tables_give_back_the_same_map() {
        let m = tetrahedron();
        let back = CMap3::from_tables(m.to_tables()).unwrap();
        assert!(back.is_valid().is_empty());
        assert_eq!(back.nb_darts(), m.nb_darts());
        assert!(m.darts().all(|d| (0..4).all(|i| m.beta(d, i) == back.beta(d, i))
            && m.vertex_of(d) == back.vertex_of(d)
            && m.mark_bits(d) == back.mark_bits(d)));
        assert_eq!(back.positions(), m.positions());
    }

    #[test]
    fn damaged_tables_are_refused_in_words() {
        let mut t = tetrahedron().to_tables();
        t.betas[3][2] = 999;
        assert!(CMap3::from_tables(t).unwrap_err().contains("links to 999"));
        let mut t = tetrahedron().to_tables();
        t.vertex[2] = 77;
        assert!(CMap3::from_tables(t).unwrap_err().contains("vertex id 77"));
        let mut t = tetrahedron().to_tables();
        t.vertex.pop();
        assert!(CMap3::from_tables(t).is_err());
        let mut t = tetrahedron().to_tables();
        // β2 no longer an involution.
        let (a, b) = (t.betas[1][2], t.betas[2][2]);
        t.betas[1][2] = b;
        t.betas[2][2] = a;
        assert!(CMap3::from_tables(t).unwrap_err().starts_with("not a valid map"));
    }
}
