//! Errors for input the solver cannot interpret.
//!
//! A [`SolverError`] means the caller handed over malformed data: a dimension that does not
//! match, a value that is not finite, a soft-row weight that is not a positive number, an
//! effective mass matrix M̃ that is not symmetric positive definite. Everything that can happen
//! to a *well-formed* problem (infeasible rows, an iteration cap, an inexact answer) is not an
//! error but a [`SolveStatus`](crate::SolveStatus) inside the [`SolveReport`](crate::SolveReport).

/// Malformed input to the velocity solve. Every variant names the offending quantity and where
/// it sits, so the caller can trace it back to the body model or the row builder.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolverError {
    /// A matrix or vector does not have the size the problem needs (n = number of DOFs).
    #[error("{what} has size {found}, expected {expected}")]
    DimensionMismatch {
        /// Which input, e.g. "force", "mass matrix rows", "row coefficients".
        what: &'static str,
        /// The size the problem needs.
        expected: usize,
        /// The size that was given.
        found: usize,
    },
    /// An input value is NaN or infinite.
    #[error("{what}[{row}, {col}] = {value} is not finite")]
    NonFinite {
        /// Which input, e.g. "mass matrix", "force", "row coefficients", "row rhs".
        what: &'static str,
        /// Row index (the DOF for vectors, the constraint row for row data).
        row: usize,
        /// Column index (0 for vectors; the DOF for row coefficients).
        col: usize,
        /// The offending value.
        value: f64,
    },
    /// M̃ is not symmetric: M̃\[row, col\] and M̃\[col, row\] differ by more than rounding.
    #[error("mass matrix is not symmetric: M[{row}, {col}] = {upper}, M[{col}, {row}] = {lower}")]
    NotSymmetric {
        /// Row of the upper-triangle entry.
        row: usize,
        /// Column of the upper-triangle entry.
        col: usize,
        /// M̃\[row, col\].
        upper: f64,
        /// M̃\[col, row\].
        lower: f64,
    },
    /// The Cholesky factorisation M̃ = L Lᵀ met a non-positive pivot: M̃ is not positive
    /// definite (for M̃ = M_r + hD + h²K this means a negative stiffness or a broken M_r).
    #[error("mass matrix is not positive definite (non-positive Cholesky pivot at DOF {pivot})")]
    NotPositiveDefinite {
        /// DOF of the first failing pivot in the factor's elimination order (the dense factor
        /// eliminates the DOFs from the last to the first, see `mass_factor.rs`).
        pivot: usize,
    },
    /// A soft inequality row has a penalty weight that is not finite and strictly positive.
    #[error("soft row {row}: weight {weight} must be finite and > 0")]
    InvalidWeight {
        /// Index of the row.
        row: usize,
        /// The weight given.
        weight: f64,
    },
    /// A compliant row has a compliance that is not finite and strictly positive.
    #[error("compliant row {row}: compliance {compliance} must be finite and > 0")]
    InvalidCompliance {
        /// Index of the row.
        row: usize,
        /// The compliance given.
        compliance: f64,
    },
    /// A friction row is malformed: a coefficient that is not finite and ≥ 0, a normal row
    /// that does not exist or is not an inequality row, or a third consecutive row of one
    /// contact.
    #[error("friction row {row}: {reason}")]
    InvalidFriction {
        /// Index of the row.
        row: usize,
        /// What is wrong.
        reason: String,
    },
    /// Friction cones are solved by the clarabel backend only: on the contact-space backend a
    /// contact's friction is its cone's inscribed pyramid, given as inequality rows
    /// ([`FrictionPyramid`](crate::FrictionPyramid)).
    #[error(
        "friction row {row}: the contact-space backend takes friction as the pyramid's \
         inequality rows (FrictionPyramid); the exact cone needs QpBackend::Clarabel"
    )]
    FrictionConeNeedsClarabel {
        /// Index of the first friction row.
        row: usize,
    },
    /// The problem's stop flag ([`Problem::stopping_when`](crate::Problem::stopping_when)) was
    /// set during the solve: it was abandoned, its answer is not usable.
    #[error("stopped on request during the solve")]
    Stopped,
    /// A buffer could not be allocated: the memory the process may use (the machine's, or a
    /// limit such as `ulimit -v`) does not hold it. Nothing was changed.
    #[error("cannot allocate {what} ({} MB): not enough memory for a problem this size", bytes / 1_000_000)]
    Allocation {
        /// Which buffer, with its shape, e.g. "the rows' coefficients (30000 × 1621)".
        what: String,
        /// Its size in bytes.
        bytes: u64,
    },
}
