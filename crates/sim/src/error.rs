//! Errors of the step pipeline.

use hagfish_geometry::GeometryError;
use hagfish_solver::{SolveStatus, SolverError};
use hagfish_tree::TreeError;

/// What can stop a scenario or a step. Every variant says at which step and simulation time it happened.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A scenario or biometrics file is unreadable or invalid (message has file:line:column).
    #[error(transparent)]
    DataFile(#[from] hagfish_anatomy::AnatomyError),
    /// The body file a scenario names cannot be read (the position is the scenario's `body`).
    #[error("{at}: body: {source}")]
    BodyFile {
        /// Where the scenario names the body file.
        at: hagfish_anatomy::Origin,
        /// The underlying error.
        source: Box<hagfish_anatomy::AnatomyError>,
    },
    /// The model could not be built.
    #[error("building the model: {0}")]
    Model(#[from] TreeError),
    /// The sparse backend cannot take the model.
    #[error("sparse backend: {0}")]
    Sparse(#[from] hagfish_sparse::SparseError),
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
    /// A run cannot be resumed from its checkpoint (unreadable, or not of this scenario).
    #[error("{}: cannot resume: {reason}", path.display())]
    Checkpoint {
        /// The checkpoint file.
        path: std::path::PathBuf,
        /// Why not.
        reason: String,
    },
    /// A `--set PATH=VALUE` override that cannot be applied (`overrides.rs`).
    #[error("--set {given}: {reason}")]
    Override {
        /// The override as given.
        given: String,
        /// Why it cannot be applied.
        reason: String,
    },
    /// The scenario with its overrides applied fails a check (the location is in the
    /// overridden scenario, as its run directory's `scenario.ron` records it).
    #[error("with --set {overrides}: {source}")]
    Overridden {
        /// The overrides, as given.
        overrides: String,
        /// The failed check.
        source: Box<SimError>,
    },
    /// The step buffers of the body would not fit in the memory available
    /// (`memory.rs` explains the estimate).
    #[error(
        "a body of {bodies} bodies ({dofs} DOFs) needs about {} MB for its step buffers, and \
         {} MB are available: use fewer bodies (the buffers grow as the square of the DOFs)",
        needed / 1_000_000,
        available / 1_000_000
    )]
    InsufficientMemory {
        /// Bodies of the model.
        bodies: usize,
        /// DOFs of the model.
        dofs: usize,
        /// The estimate (bytes).
        needed: u64,
        /// Available memory (bytes).
        available: u64,
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
    /// The controller could not return to a saved state (a retried step, a resume).
    #[error("controller: {0}")]
    Controller(#[from] hagfish_control::ControlError),
    /// Invalid options (non-positive time step, negative margin, …).
    #[error("invalid option {name} = {value}: {expected}")]
    InvalidOption {
        /// Option name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// What is expected.
        expected: &'static str,
    },
    /// The kinematic tree rejected the state or could not factor M̃.
    #[error("step {step} (t = {time} s): {source}")]
    Tree {
        /// Step index.
        step: u64,
        /// Simulation time (s).
        time: f64,
        /// The underlying error.
        source: TreeError,
    },
    /// The contact geometry rejected its input (non-finite centres, …).
    #[error("step {step} (t = {time} s): contact geometry: {source}")]
    Geometry {
        /// Step index.
        step: u64,
        /// Simulation time (s).
        time: f64,
        /// The underlying error.
        source: GeometryError,
    },
    /// The constraint solver rejected its input (malformed rows).
    #[error("step {step} (t = {time} s): solver: {source}")]
    Solver {
        /// Step index.
        step: u64,
        /// Simulation time (s).
        time: f64,
        /// The underlying error.
        source: SolverError,
    },
    /// The step's result is not physically valid ([`crate::StepAcceptance`]); the state was
    /// not advanced.
    #[error("step {step} (t = {time} s): result rejected: {rejection}")]
    StepRejected {
        /// Step index.
        step: u64,
        /// Simulation time (s).
        time: f64,
        /// The bound exceeded.
        rejection: crate::Rejection,
    },
    /// A step failed even when divided into substeps down to the smallest allowed.
    #[error("{first} (and again with {divisions} substeps of {substep_s:e} s: {last})")]
    StepFailedWithSubsteps {
        /// The error of the whole step.
        first: Box<SimError>,
        /// The most substeps tried.
        divisions: u32,
        /// Their length (s).
        substep_s: f64,
        /// The error of the last try.
        last: Box<SimError>,
    },
    /// The velocity solve did not produce a usable answer; the state was not advanced.
    #[error(
        "step {step} (t = {time} s): velocity solve failed with status {status:?} ({rows} rows)"
    )]
    SolveFailed {
        /// Step index.
        step: u64,
        /// Simulation time (s).
        time: f64,
        /// The solver's status.
        status: SolveStatus,
        /// Number of constraint rows.
        rows: usize,
    },
}
