//! `hagfish export wcon DIR [--out FILE]`: a run's midline in WCON, the Worm tracker Commons
//! format (units cm and s; the third coordinate under `@hagfish`), so that tools made for
//! tracked videos read simulated midlines ([`hagfish_report::wcon`]).

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, Subcommand};

use super::CliError;

/// Arguments of `hagfish export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// The format.
    #[command(subcommand)]
    format: Format,
}

/// The export formats.
#[derive(Debug, Subcommand)]
enum Format {
    /// The midline (body centres per frame) as WCON (JSON).
    Wcon {
        /// A run directory written by `hagfish run`.
        dir: PathBuf,
        /// The file to write (default DIR/midline.wcon).
        #[arg(long, value_name = "FILE")]
        out: Option<PathBuf>,
    },
}

/// Writes the export and says where.
pub fn run(args: &ExportArgs, out: &mut dyn Write) -> Result<(), CliError> {
    match &args.format {
        Format::Wcon { dir, out: file } => {
            let written = hagfish_report::export_wcon(dir, file.as_deref())?;
            writeln!(out, "wrote {}", written.display())?;
        }
    }
    Ok(())
}
