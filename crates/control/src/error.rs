//! Errors of the control crate.

use crate::until::{Direction, Quantity};

/// What can go wrong when setting a controller up.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ControlError {
    /// A phase end condition whose quantity cannot be read in its unit or compared its way
    /// (a knot start in diameters, a kinetic energy above a threshold).
    #[error(
        "({quantity:?}, {direction:?}, {unit}(…)) is not an end condition: {quantity:?} is \
         compared {admitted}"
    )]
    NotACondition {
        /// The quantity.
        quantity: Quantity,
        /// The direction.
        direction: Direction,
        /// The threshold's unit as written (`D`).
        unit: &'static str,
        /// What the quantity admits ("Below or Above, in Cm or L").
        admitted: &'static str,
    },
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
    /// Mode shapes that do not span a space of their number of dimensions on the body
    /// ([`crate::ModalBasis::orthonormal`]).
    #[error("mode {mode}: {reason}: not a basis")]
    NotABasis {
        /// The first mode (from 1) that is dependent on the earlier ones, 0 for bad input.
        mode: usize,
        /// What is wrong.
        reason: &'static str,
    },
}
