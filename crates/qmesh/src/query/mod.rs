//! The 2025 query engine (Damiand, Nivoliers & Pascual, §5): queries made of any
//! connected set of volumes, matched by replaying a recorded traversal.
//!
//! - [`word`]: labelling and query words with boundary conditions (Def. 3–5, §5.1.2);
//! - [`Annotator`]: Algorithm 1 and the §5.1.2 constraint table, allocation-free;
//! - [`PrefixTree`]: many words at once (§5.2.1);
//! - [`find_matches`]: every start dart, in parallel, one match per automorphism class;
//! - [`select`](fn@select): greedy / best / random non-overlapping selection (§5.2.2).
//!
//! ```
//! use qmesh::build::{BuildOptions, build_volume_map};
//! use qmesh::query::{Condition, MatchOptions, Query, QuerySet, Strategy, find_matches, select};
//! let opts = BuildOptions::default();
//! let (grid, _) = build_volume_map(&qmesh::generate::hex_grid(4, 4, 1), &opts).unwrap();
//! let (pair, _) = build_volume_map(&qmesh::generate::hex_grid(2, 1, 1), &opts).unwrap();
//! let set = QuerySet::new(vec![Query::new("pair", pair, |_| Condition::Any).unwrap()]);
//! let found = find_matches(&grid, &set, &MatchOptions::default());
//! assert_eq!(found.per_query[0], 2 * 3 * 4); // 12 pairs along x, 12 along y
//! let chosen = select(&grid, &set, &found.matches, Strategy::Greedy, None);
//! assert_eq!(chosen.len(), 8); // 16 cells, two per pair
//! ```

mod annotate;
mod annotation;
mod automorphism;
mod error;
mod fit;
mod guard;
mod matcher;
mod metric;
mod query_map;
mod select;
mod trie;
pub mod word;

pub use annotate::Annotator;
pub use automorphism::Automorphisms;
pub use error::QueryError;
pub use matcher::{Match, MatchOptions, MatchReport, MatchVolumes, QuerySet, find_matches};
pub use metric::{Metric, MetricFn};
pub use query_map::Query;
pub use select::{
    LazySearch, Selected, Separation, Strategy, select, select_by_volumes, select_random_lazily, select_separated,
};
pub use trie::PrefixTree;
pub use word::{Condition, Labelling, QueryWord};

/// The largest query, in darts (a 15-tetrahedron hexahedron has 180).
pub const MAX_QUERY_DARTS: usize = 1 << 16;
