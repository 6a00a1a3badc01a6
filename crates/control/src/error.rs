//! Errors of the control crate.

/// What can go wrong when setting a controller up.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ControlError {
    /// A saved controller state that does not fit the scenario's phases.
    #[error(
        "controller state does not fit the scenario: phase {phase} of {phases}, forming progress {forming}"
    )]
    StateMismatch {
        /// Phase index of the state.
        phase: usize,
        /// Number of phases of the scenario.
        phases: usize,
        /// Whether the state has forming progress.
        forming: bool,
    },
}
