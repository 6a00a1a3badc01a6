//! Errors of the step: building a world, and a step that fails or is rejected.

use hagfish_geometry::GeometryError;
use hagfish_solver::{SolveStatus, SolverError};
use hagfish_tree::TreeError;

/// What can stop building a world or taking a step. A step's error says at which step and
/// simulation time it happened.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// The model could not be built.
    #[error("building the model: {0}")]
    Model(#[from] TreeError),
    /// The sparse backend cannot take the model.
    #[error("sparse backend: {0}")]
    Sparse(#[from] hagfish_sparse::SparseError),
    /// The step buffers of the body would not fit in the memory the process may still
    /// allocate (`memory.rs` explains the estimate and the bounds).
    #[error(
        "a body of {bodies} bodies ({dofs} DOFs) needs about {} MB for its step buffers (the \
         memory of every step), and {} MB may be allocated under {bound}: use fewer bodies \
         (the buffers grow {growth}) or raise that limit",
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
        /// The bound that gives `available`.
        bound: crate::memory::MemoryBound,
        /// How the buffers grow with the body, on its backend.
        growth: &'static str,
    },
    /// A step buffer could not be allocated although the estimate fit (a limit it does not
    /// see, or memory taken meanwhile): an error before the first step, not an abort.
    #[error("allocating the step buffers of a body of {bodies} bodies: {source}")]
    Allocation {
        /// Bodies of the model.
        bodies: usize,
        /// The buffer that could not be allocated.
        source: SolverError,
    },
    /// A stop was asked for ([`crate::StopRequest`]) while the step was being taken: it was
    /// abandoned at a stage boundary and the state left at its start.
    #[error("step {step} (t = {time} s): stopped on request before its end")]
    Stopped {
        /// Step index.
        step: u64,
        /// Simulation time at the step's start (s).
        time: f64,
    },
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
    /// The exact friction cone asks for a backend that cannot solve it.
    #[error(
        "friction.cone = Exact needs the clarabel backend (solver.backend = Clarabel); the \
         contact-space backend solves the pyramid (cone = Pyramid)"
    )]
    ExactConeNeedsClarabel,
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

/// Where in a run a step is: its index and its start time (s), which every error of the
/// step carries ([`InStep::in_step`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct StepAt {
    /// Step index.
    pub(crate) step: u64,
    /// Simulation time at the step's start (s).
    pub(crate) time: f64,
}

/// An error of a stage, placed at its step and time as a [`SimError`].
pub(crate) trait InStep<T> {
    /// The error, if any, with the step and time of `at`.
    fn in_step(self, at: StepAt) -> Result<T, SimError>;
}

impl<T> InStep<T> for Result<T, TreeError> {
    fn in_step(self, StepAt { step, time }: StepAt) -> Result<T, SimError> {
        self.map_err(|source| SimError::Tree { step, time, source })
    }
}

impl<T> InStep<T> for Result<T, GeometryError> {
    fn in_step(self, StepAt { step, time }: StepAt) -> Result<T, SimError> {
        self.map_err(|source| SimError::Geometry { step, time, source })
    }
}

impl<T> InStep<T> for Result<T, SolverError> {
    fn in_step(self, StepAt { step, time }: StepAt) -> Result<T, SimError> {
        self.map_err(|source| match source {
            SolverError::Stopped => SimError::Stopped { step, time },
            source => SimError::Solver { step, time, source },
        })
    }
}
