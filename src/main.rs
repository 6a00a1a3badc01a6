//! `hagfish`: simulates a hagfish tying an overhand knot in its body and sliding it to the
//! head (CGS units). The subcommands live in [`cli`], one file each.
//!
//! Exit codes: 0 on success (a run that completed or was stopped on request), 3 when a run
//! diverged (its outputs are kept), 130 when SIGINT or SIGTERM stopped a run (after a frame,
//! resumable), 2 on any other error (bad input file, unwritable output,
//! or a usage error reported by clap), with an `error: file:line:column: what` message on
//! stderr.

mod cli;

use std::io::Write;
use std::process::ExitCode;

use clap::Parser;

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
