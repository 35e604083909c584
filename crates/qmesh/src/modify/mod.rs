//! The 2025 modify operations (§6): extend, delete, replace and apply, driven by rules
//! (a query, a target or a function, and a selection strategy) read from TOML rule
//! files or built in code.
//!
//! A [`Plan`] is computed once per rule from the query Q, the target T and m_QT (found
//! by matching one in the other, [`correspondence`]); [`execute`](fn@execute) then rewires each
//! selected match. Every operation leaves a valid map.

mod apply;
pub mod correspondence;
mod error;
mod execute;
mod execute_batch;
mod face_pattern;
mod plan;
mod rule;
mod rule_file;
mod volume_pattern;

pub use apply::{BUILTIN_APPLY, builtin_apply, flatten_top, merge_volumes};
pub use error::ModifyError;
pub use execute::{Executed, execute};
pub use execute_batch::{DisjointExecutor, Job};
pub use face_pattern::FacePattern;
pub use plan::{Operation, Plan};
pub use rule::{Action, ApplyFn, Rule, RuleReport, run_rules};
pub use rule_file::{RuleError, load_rules, parse_rules};
pub use volume_pattern::VolumePattern;
