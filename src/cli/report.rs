//! `hagfish report DIR`: re-makes `report.html`, one offline page with the run's summary,
//! plots, animation, scenario, manifest and a 3-D view.

use std::io::Write;
use std::path::PathBuf;

use super::CliError;
use super::render::print_written;

/// Arguments of `hagfish report`.
#[derive(Debug, clap::Args)]
pub struct ReportArgs {
    /// A run directory written by `hagfish run`.
    dir: PathBuf,
}

/// Writes the run directory's `report.html`.
pub fn run(args: &ReportArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let written = hagfish_report::report(&args.dir, &hagfish_modes::report_sections(&args.dir))?;
    print_written(&written, out)
}
