//! `hagfish recover DIR`: puts back the run that an `hagfish run --overwrite` stopped (killed)
//! before its new run's first checkpoint had set aside in `DIR/.hagfish-previous/`
//! (`docs/outputs.md`, "Guarantees"). Every `hagfish run` into DIR does the same first.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;

use crate::CliError;
use crate::run_dir::{LockedDirectory, SetAside};

/// Arguments of `hagfish recover`.
#[derive(Debug, Args)]
pub struct RecoverArgs {
    /// The run directory.
    directory: PathBuf,
}

/// Locks the directory, puts back a run set aside by a stopped replacement (removing the new
/// run's files) and says whether there was one.
pub fn run(args: &RecoverArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let _lock = LockedDirectory::lock(&args.directory, false)?;
    if SetAside::recover(&args.directory)? {
        writeln!(out, "{}: the earlier run is back", args.directory.display())?;
    } else {
        writeln!(
            out,
            "{}: nothing set aside; the directory is as it was",
            args.directory.display()
        )?;
    }
    Ok(())
}
