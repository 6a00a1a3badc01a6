//! Errors of a run: its outputs, its checkpoint, and what stops it.

use hagfish_scenario::ScenarioError;
use hagfish_sim::SimError;

/// What can stop a run: a scenario that does not build, an output that cannot be written or
/// read back, a checkpoint that cannot be resumed, a step that fails (with its step and time).
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The scenario could not be loaded or built.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A step failed (or building the world did).
    #[error(transparent)]
    Sim(#[from] SimError),
    /// An output file could not be written.
    #[error("{}: cannot write: {source}", path.display())]
    Output {
        /// The file.
        path: std::path::PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// An `.npy` file that is not a 2-D f64 array as the recorder writes them.
    #[error("{}: not a readable .npy array: {what}", path.display())]
    InvalidNpy {
        /// The file.
        path: std::path::PathBuf,
        /// What is wrong.
        what: String,
    },
    /// An `.npy` array whose rows up to the checkpoint are not those the run wrote (edited or
    /// damaged since): the message names the file and the rows that differ from what the
    /// checkpoint recorded, never the recorded hash (which would let an edit be made to match).
    #[error(
        "{}: cannot resume: its first {rows} rows are not those the checkpoint recorded (their \
         FNV-1a 64 hash differs); the file was edited or damaged: start a new run",
        path.display()
    )]
    ChangedArray {
        /// The file.
        path: std::path::PathBuf,
        /// Rows checked.
        rows: usize,
    },
    /// A run cannot be resumed from its checkpoint (unreadable, or not of this scenario).
    #[error("{}: cannot resume: {reason}", path.display())]
    Checkpoint {
        /// The checkpoint file.
        path: std::path::PathBuf,
        /// Why not.
        reason: String,
    },
    /// The scenario needs more steps than the run may take ([`crate::RunOptions::max_steps`]).
    #[error(
        "the scenario needs {steps:e} steps (duration_s / time_step_s), more than the cap of \
         {cap}: shorten it, raise the time step, or allow more with --max-steps"
    )]
    TooManySteps {
        /// duration / time step.
        steps: f64,
        /// The cap.
        cap: u64,
    },
    /// A tie phase did not tie its knot ([`hagfish_control::TiePhase`]).
    #[error("the tie phase did not tie {0}")]
    TieFailed(hagfish_control::TieFailure),
}
