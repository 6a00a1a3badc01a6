//! Scaffolding of the hagfish workspace's benchmarks and tests, kept out of the simulator's
//! public API: the knotted benchmark state (a scenario file found relative to the workspace
//! root), the same animal knotted at 1000 bodies, and the family of bodies the knot scenarios
//! are judged on (`tests/integration/tie_family.rs`, `tests/integration/knot_size.rs`,
//! `cargo xtask family`; the measures of a knot run are `hagfish_report::KnotRun` and
//! `hagfish_report::LoosenTighten`).

mod family;
mod knotted_state;

pub use family::{Variant, edited, family, length_edits};

pub use knotted_state::{
    KNOTTED_SCENARIO, KNOTTED_TIME_S, LONG_KNOTTED_BODIES, LONG_KNOTTED_TIME_S, knotted_world,
    long_knotted_world,
};
