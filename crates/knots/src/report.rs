//! The result of the knot analysis.

use crate::{AlexanderPolynomial, KnotType};

/// Knot type of an open curve as decided by the majority of its closures, with where the
/// knot sits along the curve.
#[derive(Debug, Clone, PartialEq)]
pub struct KnotReport {
    /// The majority knot type.
    pub knot: KnotType,
    /// Normalised Alexander polynomial of the majority (identifies [`KnotReport::knot`]).
    pub polynomial: AlexanderPolynomial,
    /// Knot determinant |Δ(−1)| of the majority polynomial (1 for the unknot, 3 for the
    /// trefoil).
    pub determinant: u64,
    /// Fraction of the evaluated closure directions whose closure has the majority
    /// polynomial, in (0, 1]. Well below 1 means the curve's ends are buried in, or close
    /// to, the knotted region, so its knot type is ambiguous.
    pub agreement: f64,
    /// Number of closure directions with a generic projection (those that voted); equal to
    /// [`crate::KnotOptions::directions`] unless the curve nearly passes through itself.
    pub directions_evaluated: usize,
    /// First and last vertex index of the smallest sub-arc whose own closure still has the
    /// majority type, or `None` for the unknot or when not requested.
    pub extent: Option<(usize, usize)>,
    /// Arc length from vertex 0 to the midpoint of [`KnotReport::extent`] (same units as the
    /// input, e.g. cm), or `None` with it.
    pub position: Option<f64>,
    /// Mean writhe of the closures of [`KnotReport::extent`] (the knotted core), or `None`
    /// with it: its sign tells a chiral knot's handedness (positive: right-handed trefoil),
    /// which the polynomial does not.
    pub writhe: Option<f64>,
}

impl KnotReport {
    /// The handedness of a chiral knot from the sign of [`KnotReport::writhe`]: `Some(true)`
    /// for right-handed (positive writhe), `Some(false)` for left-handed, `None` without a
    /// core or with a writhe within ±0.5 of zero (achiral knots such as 4_1 sit there).
    pub fn right_handed(&self) -> Option<bool> {
        self.writhe.filter(|w| w.abs() > 0.5).map(|w| w > 0.0)
    }
}
