//! Integration tests of `hagfish`, the command end to end: one test binary, a module per
//! subject; `common` has the helpers they share (running the built `hagfish`, fresh
//! directories, reading run directories).

mod common;

mod around_cylinder;
mod body_command;
mod body_counts;
mod commands;
mod errors;
mod export_command;
mod follow_tie;
mod hostile_inputs;
mod huge_bodies;
mod knot_core;
mod knot_plans;
mod knot_size;
mod modes_command;
mod overrides;
mod overwrite_kill;
mod pull;
mod refusals;
mod render_command;
mod resume;
mod run_command;
mod run_directory;
mod step_acceptance;
mod sweep_command;
mod sweep_replicates;
mod tie_family;
mod user_names;
