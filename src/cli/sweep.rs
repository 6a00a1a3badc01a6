//! `hagfish sweep plan GRID.ron --out DIR`, `hagfish sweep run DIR [--shard i/n] [--jobs N]`,
//! `hagfish sweep collect DIR`: a parameter study without Python ([`crate::sweep`]). Each run
//! is a run directory under `DIR/runs/`; `run` makes only the runs that have not ended, so a
//! stopped sweep is finished by running it again, and shards of one plan can run as the tasks
//! of a Slurm job array or under GNU parallel.

use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use clap::{Args, Subcommand};

use crate::CliError;
use crate::sweep::{Grid, Plan, RunResult, Shard, run_shard};
use crate::sweep_summary::{INTERVALS_FILE, SUMMARY_FILE, collect};

/// Arguments of `hagfish sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// What to do.
    #[command(subcommand)]
    action: Action,
}

/// The steps of a sweep.
#[derive(Debug, Subcommand)]
enum Action {
    /// Check a grid file and write the sweep's plan (plan.json: each combination, `replicates`
    /// times). A folder planned before with fewer replicates keeps its runs.
    Plan {
        /// The grid file (RON): `Sweep(scenario: "…", grid: [("PATH", ["VALUE", …]), …])`.
        grid: PathBuf,
        /// The sweep folder.
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Make the runs of the plan in DIR that have not ended (all, or one shard of them).
    Run {
        /// The sweep folder.
        directory: PathBuf,
        /// Only shard i of n (1 ≤ i ≤ n): the runs whose index is i − 1 modulo n. Collect
        /// once every shard has run.
        #[arg(long, value_name = "i/n")]
        shard: Option<String>,
        /// Runs made at the same time, each on one thread.
        #[arg(long, value_name = "N", default_value_t = 1)]
        jobs: usize,
    },
    /// Read every run of DIR into DIR/summary.csv, each grid point's means and 95 % intervals
    /// into DIR/intervals.csv, and plot each statistic against each swept parameter
    /// (DIR/plots).
    Collect {
        /// The sweep folder.
        directory: PathBuf,
    },
}

/// Runs the sweep action.
pub fn run(args: &SweepArgs, out: &mut dyn Write) -> Result<(), CliError> {
    match &args.action {
        Action::Plan { grid, out: folder } => {
            let plan = Plan::of(&Grid::read(grid)?, grid)?;
            plan.write(folder)?;
            let points = plan.points().into_iter().max().map_or(0, |p| p + 1);
            writeln!(
                out,
                "{} runs ({points} grid points × {} replicates) of {} over {} in {}",
                plan.runs.len(),
                plan.runs.len() / points.max(1),
                plan.scenario.display(),
                plan.parameters.join(", "),
                folder.display()
            )?;
        }
        Action::Run { directory, shard, jobs } => {
            let shard = shard.as_deref().map_or(Ok(Shard::ALL), Shard::parse)?;
            if *jobs == 0 {
                return Err(CliError::Sweep("--jobs 0: at least one job is needed".into()));
            }
            let stop = Arc::new(AtomicBool::new(false));
            let flag = Arc::clone(&stop);
            let _stop_signal =
                super::stop_signal::on_stop_signal(move || flag.store(true, Ordering::Relaxed))?;
            let plan = Plan::read(directory)?;
            let total = shard.indices(plan.runs.len()).count();
            if shard != Shard::ALL {
                eprintln!(
                    "shard {}/{}: {total} of the plan's {} runs; collect once every shard has run",
                    shard.number,
                    shard.count,
                    plan.runs.len()
                );
            }
            let done = AtomicUsize::new(0);
            let report = |index: usize, result: &RunResult, seconds: f64| {
                let count = done.fetch_add(1, Ordering::Relaxed) + 1;
                let run = &plan.runs[index];
                eprintln!(
                    "[{count}/{total}] run {} ({}): {} in {seconds:.1} s",
                    run.id,
                    run.overrides.join(" "),
                    describe(result)
                );
            };
            let results = run_shard(directory, shard, *jobs, &stop, &report)?;
            let failed: Vec<String> = results
                .iter()
                .filter(|(_, r)| matches!(r, RunResult::Failed(_)))
                .map(|(i, _)| plan.runs[*i].id.clone())
                .collect();
            writeln!(out, "{} runs made or found ended, {} failed", results.len(), failed.len())?;
            if stop.load(Ordering::Relaxed) {
                return Err(CliError::Sweep(format!(
                    "interrupted; run `hagfish sweep run {}` again to finish",
                    directory.display()
                )));
            }
            if !failed.is_empty() {
                return Err(CliError::Sweep(format!("runs that failed: {}", failed.join(", "))));
            }
        }
        Action::Collect { directory } => {
            let collected = collect(directory)?;
            let points = collected.points.iter().map(|p| p.point + 1).max().unwrap_or(0);
            if points <= MAX_POINTS_SHOWN {
                write!(out, "{}", collected.table())?;
            }
            writeln!(
                out,
                "{} runs ({} not made yet) in {}; per grid point, every statistic with its 95 % \
                 interval, in {}",
                collected.runs,
                collected.missing,
                directory.join(SUMMARY_FILE).display(),
                directory.join(INTERVALS_FILE).display()
            )?;
        }
    }
    Ok(())
}

/// The most grid points `collect` lists at the terminal (a larger sweep is read in its
/// tables).
const MAX_POINTS_SHOWN: usize = 24;

/// How a run ended, in a few words.
fn describe(result: &RunResult) -> String {
    match result {
        RunResult::Skipped(status) => format!("already {}", status.name()),
        RunResult::Ran(status) => status.name().to_owned(),
        RunResult::Failed(message) => format!("failed: {message}"),
    }
}
