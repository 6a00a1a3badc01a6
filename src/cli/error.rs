//! The error of any subcommand; `main` prints it as one line and exits with code 2.

use hagfish_anatomy::AnatomyError;

/// What can stop a subcommand. Each message already names its file (and line and column
/// where there is one), so it is printed as is.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The biometrics file could not be read, parsed, validated or turned into a model.
    #[error(transparent)]
    Anatomy(#[from] AnatomyError),
    /// The scenario could not be loaded or the run stopped.
    #[error(transparent)]
    Sim(#[from] hagfish_sim::SimError),
    /// The run directory could not be read or its pictures, report or exports written.
    #[error(transparent)]
    Report(#[from] hagfish_report::ReportError),
    /// Writing the report to stdout failed (e.g. a closed pipe).
    #[error("cannot write the output: {0}")]
    Output(#[from] std::io::Error),
}
