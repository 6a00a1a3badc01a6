//! `hagfish` as a library: everything the `hagfish` program does, for callers that are not a
//! shell — the Python package (`crates/python`), sweeps, and other Rust programs.
//!
//! - [`runner`]: run a scenario into a run directory (`docs/outputs.md`), or resume one;
//! - [`study`]: the numbers a study compares, read from a run directory;
//! - [`sweep`]: many runs of one scenario, planned, made in shards or threads, collected;
//! - [`manifest`], [`run_dir`]: the run directory's `manifest.json` and its lock;
//! - [`cli`]: the command line, one file per subcommand.
//!
//! Units are CGS (cm, g, s; dyn, dyn·cm) throughout, as in every output column name.

pub mod cli;
mod error;
pub mod manifest;
pub mod run_dir;
pub mod runner;
pub mod study;
pub mod sweep;
pub mod sweep_summary;
mod utc;

pub use error::CliError;
