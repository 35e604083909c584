//! The 2025 query-modify engine, in one test binary (one link instead of three):
//! matching (the §5.1.2 table, Fig. 3, prefix tree, threads, selection, 2022
//! agreement), modifying (extend / delete / replace / apply, rule files), property
//! tests on random maps, the tetrahedra → hexahedra recombination (§7.1), and the
//! terrain of §7.4.

#[path = "../common/mod.rs"]
mod common;
mod matching;
mod modifying;
mod properties;
mod queries;
mod recombination;
mod terrain;
