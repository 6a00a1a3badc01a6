//! Invalid input to the geometry crate.

use glam::DVec3;

/// Why an input to the geometry crate was rejected.
///
/// Every variant carries the offending index or value so that a caller can report which
/// body or option is wrong without re-checking.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// A centreline needs at least one segment, i.e. two centres.
    #[error("a centreline needs at least 2 body centres, got {count}")]
    TooFewCentres {
        /// Number of centres supplied.
        count: usize,
    },
    /// A per-body slice does not have one entry per body centre.
    #[error("`{what}` has {got} entries but there are {expected} body centres")]
    LengthMismatch {
        /// Name of the per-body input (e.g. `radii`, `body_lengths`).
        what: &'static str,
        /// Number of body centres.
        expected: usize,
        /// Number of entries supplied.
        got: usize,
    },
    /// A body centre has a NaN or infinite coordinate.
    #[error("body centre {index} is not finite: {value}")]
    NonFiniteCentre {
        /// Body index.
        index: usize,
        /// The rejected centre.
        value: DVec3,
    },
    /// A body radius is zero, negative or not finite.
    #[error("body radius {index} must be positive and finite, got {value}")]
    NonPositiveRadius {
        /// Body index.
        index: usize,
        /// The rejected radius (cm).
        value: f64,
    },
    /// A body length is negative or not finite.
    #[error("body length {index} must be non-negative and finite, got {value}")]
    InvalidBodyLength {
        /// Body index.
        index: usize,
        /// The rejected length (cm).
        value: f64,
    },
    /// An option or a wall parameter is outside its valid range.
    #[error("option `{name}` must be {requirement}, got {value}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// What the option must satisfy.
        requirement: &'static str,
        /// The rejected value.
        value: f64,
    },
}

impl GeometryError {
    /// Returns `Ok(())` when `valid`, otherwise [`GeometryError::InvalidOption`] naming the
    /// option; used by every options constructor so the checks read as one line each.
    pub(crate) fn require_option(
        valid: bool,
        name: &'static str,
        requirement: &'static str,
        value: f64,
    ) -> Result<(), GeometryError> {
        if valid { Ok(()) } else { Err(GeometryError::InvalidOption { name, requirement, value }) }
    }

    /// [`GeometryError::require_option`] for options that must be finite and ≥ 0, given as
    /// (name, value) pairs: the first that is not is the error.
    pub(crate) fn require_non_negative(
        options: &[(&'static str, f64)],
    ) -> Result<(), GeometryError> {
        for &(name, value) in options {
            let valid = value.is_finite() && value >= 0.0;
            Self::require_option(valid, name, "finite and non-negative", value)?;
        }
        Ok(())
    }

    /// Checks that a per-body slice named `what` has `expected` entries.
    pub(crate) fn require_length(
        what: &'static str,
        expected: usize,
        got: usize,
    ) -> Result<(), GeometryError> {
        if expected == got {
            Ok(())
        } else {
            Err(GeometryError::LengthMismatch { what, expected, got })
        }
    }
}
