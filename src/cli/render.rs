//! `hagfish render DIR`: re-makes the pictures and exports of a run directory — plots (PNG
//! and SVG), `animation.gif`, ParaView frames (`vtk/`) and `run.glb` — and prints what it
//! wrote with the time each part took.

use std::io::Write;
use std::path::PathBuf;

use hagfish_report::Written;

use super::CliError;

/// Arguments of `hagfish render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// A run directory written by `hagfish run`.
    dir: PathBuf,
}

/// Renders the run directory's pictures and exports.
pub fn run(args: &RenderArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let written = hagfish_report::render(&args.dir)?;
    print_written(&written, out)
}

/// One line per file written (VTK frames as a count), then the timings.
pub fn print_written(written: &Written, out: &mut dyn Write) -> Result<(), CliError> {
    for file in &written.files {
        let bytes = std::fs::metadata(file).map(|m| m.len()).unwrap_or(0);
        writeln!(out, "wrote {} ({bytes} bytes)", file.display())?;
    }
    if written.vtk_frames > 0 {
        writeln!(out, "wrote {} VTK frame files", written.vtk_frames)?;
    }
    let parts: Vec<String> =
        written.timings.iter().map(|(name, s)| format!("{name} {:.3}", s)).collect();
    writeln!(out, "seconds: {}  (total {:.3})", parts.join(", "), written.total_seconds())?;
    Ok(())
}
