//! The command line: one `Command` variant and one file per subcommand (`body`, `run`,
//! `params`, `knot`, `render`, `report`, `export`, `sweep`, `modes`, `recover`), all sharing [`CliError`].

mod body;
mod export;
mod knot;
mod modes;
mod params;
mod progress;
mod recover;
mod render;
mod report;
mod run;
mod stop_signal;
mod sweep;

use std::io::{BufWriter, Write};

use clap::{Parser, Subcommand};

pub use crate::CliError;

/// Command-line arguments of the `hagfish` binary.
#[derive(Debug, Parser)]
#[command(name = "hagfish", version, about)]
pub struct Cli {
    /// The subcommand to run.
    #[command(subcommand)]
    command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
enum Command {
    /// Print the bodies derived from a body file (hagfish or rod): radius, mass, joint, limits.
    Body(body::BodyArgs),
    /// Run a scenario into a run directory (CSV, .npy, manifest, checkpoint), or resume one.
    Run(run::RunArgs),
    /// Print every scenario parameter: name, unit, default and meaning.
    Params,
    /// Print the knot type of every frame of a centreline CSV.
    Knot(knot::KnotArgs),
    /// Re-make a run directory's plots, animation.gif, ParaView frames and run.glb.
    Render(render::RenderArgs),
    /// Export a run directory for other tools: `export wcon DIR` (the midline as WCON).
    Export(export::ExportArgs),
    /// Parameter studies: plan a grid of runs, make them (in shards or threads), collect them.
    Sweep(sweep::SweepArgs),
    /// Re-make a run directory's report.html (one offline page with a 3-D view).
    Report(report::ReportArgs),
    /// The modes (POD) of a run's thigmotaxis force field, their energies and a wave fit.
    Modes(modes::ModesArgs),
    /// Put back the run an `--overwrite` killed before its first checkpoint set aside.
    Recover(recover::RecoverArgs),
}

/// Runs the chosen subcommand, writing its report to stdout (buffered, flushed at the end).
pub fn run(cli: Cli) -> Result<(), CliError> {
    let mut out = BufWriter::new(std::io::stdout().lock());
    match cli.command {
        Command::Body(args) => body::run(&args, &mut out)?,
        Command::Run(args) => run::run(&args, &mut out)?,
        Command::Params => params::run(&mut out)?,
        Command::Knot(args) => knot::run(&args, &mut out)?,
        Command::Render(args) => render::run(&args, &mut out)?,
        Command::Report(args) => report::run(&args, &mut out)?,
        Command::Export(args) => export::run(&args, &mut out)?,
        Command::Sweep(args) => sweep::run(&args, &mut out)?,
        Command::Modes(args) => modes::run(&args, &mut out)?,
        Command::Recover(args) => recover::run(&args, &mut out)?,
    }
    out.flush()?;
    Ok(())
}
