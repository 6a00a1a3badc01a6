//! Errors of the kinematic tree.

/// What can go wrong when building a model or stepping it. Every variant names the offending
/// body, joint or degree of freedom, and stepping errors carry the step time.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TreeError {
    /// A body's parent index is not smaller than its own index (the tree must be topologically
    /// ordered) or refers to a body that does not exist.
    #[error("body {body}: parent {parent} must be an earlier body (parent index < child index)")]
    BadParent {
        /// Index of the body being added.
        body: usize,
        /// The parent index that was given.
        parent: usize,
    },
    /// A physical quantity is out of its valid range (non-finite, non-positive mass, …).
    #[error("body {body}: {quantity} = {value} is invalid ({expected})")]
    InvalidBody {
        /// Index of the body.
        body: usize,
        /// Name of the quantity, e.g. "mass".
        quantity: &'static str,
        /// The value given.
        value: f64,
        /// What was expected, e.g. "finite and > 0".
        expected: &'static str,
    },
    /// A per-DOF parameter is out of its valid range.
    #[error("body {body}, DOF {dof}: {quantity} = {value} is invalid ({expected})")]
    InvalidDof {
        /// Index of the body whose joint owns the DOF.
        body: usize,
        /// Index of the DOF within the joint.
        dof: usize,
        /// Name of the quantity, e.g. "stiffness".
        quantity: &'static str,
        /// The value given.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// A model needs at least one body.
    #[error("a model needs at least one body")]
    Empty,
    /// A state or input vector has the wrong length for the model.
    #[error("{what} has length {got}, the model needs {expected}")]
    DimensionMismatch {
        /// Which vector.
        what: &'static str,
        /// The length given.
        got: usize,
        /// The length the model needs.
        expected: usize,
    },
    /// A body index is out of range.
    #[error("{what}: body {body} does not exist (the model has {count} bodies)")]
    NoSuchBody {
        /// Where the index was used.
        what: &'static str,
        /// The index given.
        body: usize,
        /// Number of bodies in the model.
        count: usize,
    },
    /// The effective mass matrix M̃ was not positive definite (should not happen for a valid
    /// model: it means non-finite state or a degenerate body).
    #[error(
        "step at t = {time} s: the effective mass matrix is not positive definite (pivot {pivot})"
    )]
    NotPositiveDefinite {
        /// Simulation time of the step (s).
        time: f64,
        /// Index of the failing pivot.
        pivot: usize,
    },
    /// The state became non-finite.
    #[error("step at t = {time} s: {what} is not finite at DOF {dof}")]
    NonFinite {
        /// Simulation time of the step (s).
        time: f64,
        /// Which quantity.
        what: &'static str,
        /// First offending DOF.
        dof: usize,
    },
}
