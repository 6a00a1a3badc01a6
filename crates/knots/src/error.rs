//! Invalid input to the knot analysis.

use glam::DVec3;

/// Why a curve or an option was rejected by the knot analysis.
///
/// Every variant carries the offending count, index or value so that a caller can report
/// what is wrong without re-checking.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KnotError {
    /// An open centreline needs at least 4 points (3 segments) to be worth analysing, and a
    /// closed polygon at least 3.
    #[error("the curve needs at least {required} points, got {count}")]
    TooFewPoints {
        /// Number of points supplied.
        count: usize,
        /// Minimum number of points for this kind of curve.
        required: usize,
    },
    /// A point has a NaN or infinite coordinate.
    #[error("point {index} is not finite: {value}")]
    NonFinitePoint {
        /// Index of the point in the input slice.
        index: usize,
        /// The rejected point.
        value: DVec3,
    },
    /// All points coincide, or the coordinates are so large that the curve's extent
    /// overflows; the curve has no meaningful shape to analyse.
    #[error("the curve has no finite, non-zero extent (diameter {diameter})")]
    DegenerateExtent {
        /// Diagonal of the axis-aligned bounding box of the points.
        diameter: f64,
    },
    /// No closure direction produced a generic projection: the curve (or its closure) passes
    /// through itself, so crossings cannot be classified as over or under.
    #[error("no generic projection found in any of the {directions} directions tried")]
    NoGenericProjection {
        /// Number of closure (or projection) directions tried.
        directions: usize,
    },
    /// Every projection tried had more crossings than the analysis takes
    /// ([`crate::MAX_CROSSINGS`]): the curve is far more tangled than a body knot, and its
    /// determinant would need O(m²) memory.
    #[error(
        "the curve is too tangled to analyse: a projection shows more than {max} crossings \
         (the Alexander determinant needs O(m²) memory and O(m³) time in m crossings)"
    )]
    TooManyCrossings {
        /// The limit, [`crate::MAX_CROSSINGS`].
        max: usize,
    },
    /// An option is outside its valid range.
    #[error("option `{name}` must be {requirement}, got {value}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// What the option must satisfy.
        requirement: &'static str,
        /// The rejected value.
        value: usize,
    },
}

impl KnotError {
    /// Checks that `points` has at least `required` points, all finite.
    pub(crate) fn check_points(points: &[DVec3], required: usize) -> Result<(), KnotError> {
        if points.len() < required {
            return Err(KnotError::TooFewPoints { count: points.len(), required });
        }
        match points.iter().position(|p| !p.is_finite()) {
            Some(index) => Err(KnotError::NonFinitePoint { index, value: points[index] }),
            None => Ok(()),
        }
    }

    /// Returns `Ok(())` when `valid`, otherwise [`KnotError::InvalidOption`] naming the
    /// option.
    pub(crate) fn require_option(
        valid: bool,
        name: &'static str,
        requirement: &'static str,
        value: usize,
    ) -> Result<(), KnotError> {
        if valid { Ok(()) } else { Err(KnotError::InvalidOption { name, requirement, value }) }
    }
}
