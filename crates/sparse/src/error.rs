//! Errors of the sparse backend.

use thiserror::Error;

/// What can go wrong building or factoring the maximal-coordinate system.
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
    /// The articulated pivot `D_c = S_cᵀ Iᴬ_c S_c + K̃_c` is not positive at a DOF.
    #[error("effective mass is not positive definite (pivot {pivot} at DOF {dof})")]
    NotPositiveDefinite {
        /// The DOF.
        dof: usize,
        /// The offending pivot.
        pivot: f64,
    },
}
