//! `hagfish`: simulates a hagfish tying an overhand knot in its body and sliding it to the
//! head (CGS units). The subcommands live in [`hagfish::cli`], one file each.
//!
//! Exit codes: 0 on success (a run that completed or was stopped on request), 3 when a run
//! diverged (its outputs are kept), 4 when a tie phase could not tie its knot, 130 when SIGINT
//! or SIGTERM stopped a run (after a frame, resumable), 2 on any other error (bad input file,
//! unwritable output, or a usage error reported by clap), with an `error: file:line:column:
//! what` message on stderr.

use std::io::Write;
use std::process::ExitCode;

use clap::Parser;
use hagfish::cli;

fn main() -> ExitCode {
    match cli::run(cli::Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // Nothing sensible is left to do if stderr itself is closed.
            let _ = writeln!(std::io::stderr(), "error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}
