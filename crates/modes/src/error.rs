//! The error of this crate: every variant says what it concerns (a file, a phase, a field).

use std::path::PathBuf;

/// What can stop a decomposition: an unreadable run directory, a selection without frames
/// or without force, a factorization that failed, an output that cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum ModesError {
    /// The run directory does not exist or is not a directory.
    #[error("{}: not a run directory ({what})", path.display())]
    NoRunDirectory {
        /// The path given.
        path: PathBuf,
        /// Why.
        what: String,
    },
    /// A CSV file of the run directory could not be read or is malformed.
    #[error(transparent)]
    Csv(#[from] hagfish_report::ReportError),
    /// `thigmo_force.npy` could not be read, or a file could not be written.
    #[error(transparent)]
    Run(#[from] hagfish_run::RunError),
    /// The run's `scenario.ron` or the body file it names could not be loaded.
    #[error("{}: {source}", path.display())]
    Scenario {
        /// The scenario file.
        path: PathBuf,
        /// Why.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// Two files of the run directory disagree (frames, DOFs).
    #[error("{}: {what}", path.display())]
    Mismatch {
        /// The file that does not fit.
        path: PathBuf,
        /// What does not fit.
        what: String,
    },
    /// The selection (phase, DOF kind) has no frame.
    #[error("no frame of phase {phase:?} in the run (its phases: {available})")]
    NoFrames {
        /// The phase asked for (`(thigmotaxis)` for the default: frames with force).
        phase: String,
        /// The phases the run has, in order.
        available: String,
    },
    /// The selected force field is zero everywhere: there is nothing to decompose.
    #[error("the thigmotaxis force field of {what} is zero on every frame and DOF")]
    ZeroField {
        /// The selection (phase and kind).
        what: String,
    },
    /// A field or basis given to a function is malformed (sizes, non-finite values, order).
    #[error("{0}")]
    Invalid(String),
    /// Two selections cannot be compared (different kinds, DOFs that share arc lengths).
    #[error("cannot compare: {0}")]
    Incompatible(String),
    /// faer's singular value decomposition did not converge.
    #[error("the SVD of {what} did not converge: {reason}")]
    Svd {
        /// The matrix.
        what: String,
        /// faer's error.
        reason: String,
    },
    /// An output file or directory could not be written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The file or directory.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}
