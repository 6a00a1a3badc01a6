//! `cargo xtask <task>`: project tasks that are programs rather than tests.
//!
//! - `regress [--check | --bless] [SCENARIO…]`: runs every scenario of `data/scenarios`,
//!   compares its metrics with the golden in `data/regress/<scenario>.ron` (`--check`, the
//!   default) or rewrites the goldens (`--bless`). See `regress.rs`.

mod golden;
mod metrics;
mod regress;
mod table;
mod tolerance;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Command line of `cargo xtask`.
#[derive(Parser)]
#[command(name = "cargo xtask", about = "hagfish project tasks")]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

/// The tasks.
#[derive(Subcommand)]
enum Task {
    /// Runs the scenarios and compares their metrics with the goldens in `data/regress`.
    Regress {
        /// Compare with the goldens and fail on a difference (the default).
        #[arg(long, conflicts_with = "bless")]
        check: bool,
        /// Rewrite the goldens from this build's results.
        #[arg(long)]
        bless: bool,
        /// Scenario names (file stems in `data/scenarios`); all when none are given.
        scenarios: Vec<String>,
    },
}

/// The workspace root (the parent of this package's directory).
fn workspace_root() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().map_or(manifest.clone(), PathBuf::from)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.task {
        Task::Regress { check: _, bless, scenarios } => {
            let mode = if bless { regress::Mode::Bless } else { regress::Mode::Check };
            regress::run(&workspace_root(), mode, &scenarios)
        }
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
