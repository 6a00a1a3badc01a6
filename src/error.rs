//! The error of the program and its library (runs, sweeps, every subcommand); `main` prints it as one line and exits with its
//! [`exit_code`](CliError::exit_code): 3 for a diverged run, 4 for a knot a tie phase could
//! not tie, 130 for a run stopped by a signal, 2 for everything else.

use std::path::PathBuf;

use hagfish_anatomy::AnatomyError;

/// What can stop a subcommand. Each message already names its file (and line and column
/// where there is one), so it is printed as is.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The body file could not be read, parsed, validated or turned into a model.
    #[error(transparent)]
    Anatomy(#[from] AnatomyError),
    /// The scenario could not be loaded or built.
    #[error(transparent)]
    Scenario(#[from] hagfish_scenario::ScenarioError),
    /// The run could not be set up or recorded.
    #[error(transparent)]
    Run(#[from] hagfish_run::RunError),
    /// A world could not be built or stepped outside a run.
    #[error(transparent)]
    Sim(#[from] hagfish_sim::SimError),
    /// A step of the run failed; everything up to the last frame is kept.
    #[error(
        "the run diverged: {reason}\n(outputs up to the last frame, checkpoint.ron and the failing state in diverged.ron are in {})",
        directory.display()
    )]
    Diverged {
        /// The run directory.
        directory: PathBuf,
        /// What failed.
        reason: String,
    },
    /// A tie phase did not tie its knot; everything recorded is kept.
    #[error("{reason}\n(the outputs of the attempts are in {})", directory.display())]
    TieFailed {
        /// The run directory.
        directory: PathBuf,
        /// What failed.
        reason: String,
    },
    /// SIGINT or SIGTERM stopped the run after a frame; it is resumable.
    #[error(
        "interrupted by a signal after {frames} frames; continue with: hagfish run --resume {}",
        directory.display()
    )]
    Interrupted {
        /// The run directory.
        directory: PathBuf,
        /// Frames recorded.
        frames: usize,
    },
    /// The handler of SIGINT and SIGTERM could not be installed.
    #[error("cannot handle interrupts: {0}")]
    Signal(#[from] ctrlc::Error),
    /// A run directory (manifest, checkpoint, scenario copy) that cannot be used.
    #[error("{}: {reason}", path.display())]
    RunDirectory {
        /// The file or directory.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A malformed sweep grid file, at `file:line:column`.
    #[error("{}:{line}:{column}: {message}", path.display())]
    Grid {
        /// The grid file.
        path: PathBuf,
        /// Line, from 1.
        line: usize,
        /// Column, from 1.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A sweep that cannot be planned, run or collected (the message names the run).
    #[error("{0}")]
    Sweep(String),
    /// Arguments that do not go together.
    #[error("{0}")]
    Usage(&'static str),
    /// The run directory could not be read or its pictures, report or exports written.
    #[error(transparent)]
    Report(#[from] hagfish_report::ReportError),
    /// The force field of a run directory could not be decomposed or its modes written.
    #[error(transparent)]
    Modes(#[from] hagfish_modes::ModesError),
    /// Writing the report to stdout failed (e.g. a closed pipe).
    #[error("cannot write the output: {0}")]
    Output(#[from] std::io::Error),
}

impl CliError {
    /// The process exit code: 3 when the run diverged, 4 when a tie phase failed, 130 (as for
    /// Ctrl-C) when a signal stopped it, 2 for any other error.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Diverged { .. } => 3,
            CliError::TieFailed { .. } => 4,
            CliError::Interrupted { .. } => 130,
            _ => 2,
        }
    }
}
