//! Errors of the sparse backend.

use thiserror::Error;

/// What can go wrong building the maximal-coordinate system of a model (a failed numeric
/// factorisation is a `hagfish_solver::SolverError`, as on the dense path).
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum SparseError {
    /// A joint has more DOFs than a free joint (6).
    #[error("body {body}: its joint has {dofs} DOFs, at most 6 are supported")]
    TooManyJointDofs {
        /// The body whose joint it is.
        body: usize,
        /// Its DOF count.
        dofs: usize,
    },
}
