//! Closing an open curve "at infinity" along a direction.
//!
//! An open curve has no knot type; closing it does. The closure along a unit direction d
//! continues both ends straight along d to the plane (x − c)·d = R far beyond the curve
//! (c the centroid, R = [`CLOSURE_DISTANCE`] diameters) and joins the two far points within
//! that plane. For almost every d the result is a polygon whose knot type depends only on
//! the curve, except for the directions whose rays pass through the knotted region; the
//! analysis therefore votes over many d.

use glam::DVec3;

use crate::KnotError;

/// Distance R of the far closure plane from the centroid, in curve diameters.
pub const CLOSURE_DISTANCE: f64 = 100.0;

/// Consecutive points closer than this (in diameters) are merged: a zero-length edge would
/// make every projection look non-generic.
const DUPLICATE_DISTANCE: f64 = 1e-12;

/// An open (or closed) polygon translated to its centroid and scaled to unit diameter, so
/// that the analysis is independent of position and units (cm or m alike); consecutive
/// duplicate points are merged.
#[derive(Debug, Clone)]
pub(crate) struct NormalisedCurve {
    points: Vec<DVec3>,
}

impl NormalisedCurve {
    /// Normalises `points` (all finite). The diameter used is the diagonal of the axis-aligned
    /// bounding box, within a factor √3 of the true diameter.
    ///
    /// # Errors
    /// [`KnotError::DegenerateExtent`] if all points coincide or the diagonal overflows.
    pub(crate) fn new(points: &[DVec3]) -> Result<Self, KnotError> {
        let (min, max) = points
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let diameter = (max - min).length();
        if !(diameter.is_finite() && diameter > 0.0) {
            return Err(KnotError::DegenerateExtent { diameter });
        }
        // The centre of the box rather than the centroid: cheaper, and just as good a centre.
        let centre = 0.5 * (min + max);
        let mut normalised: Vec<DVec3> = Vec::with_capacity(points.len());
        for &p in points {
            let q = (p - centre) / diameter;
            if normalised.last().is_none_or(|last| last.distance(q) > DUPLICATE_DISTANCE) {
                normalised.push(q);
            }
        }
        Ok(Self { points: normalised })
    }

    /// The normalised points read as a closed polygon: without a last point that repeats
    /// the first (the closing edge is implicit).
    pub(crate) fn as_closed_polygon(&self) -> &[DVec3] {
        match (self.points.first(), self.points.split_last()) {
            (Some(first), Some((last, rest))) if first.distance(*last) <= DUPLICATE_DISTANCE => {
                rest
            }
            _ => &self.points,
        }
    }

    /// Writes into `polygon` the closure along the unit vector `direction`:
    /// [far start, p₀, …, pₙ₋₁, far end], implicitly closed by the far edge, with
    /// far(p) = p + (R − p·d) d.
    pub(crate) fn close(&self, direction: DVec3, polygon: &mut Vec<DVec3>) {
        let far = |p: DVec3| p + (CLOSURE_DISTANCE - p.dot(direction)) * direction;
        polygon.clear();
        if let (Some(&first), Some(&last)) = (self.points.first(), self.points.last()) {
            let (far_start, far_end) = (far(first), far(last));
            if far_start.distance(far_end) > DUPLICATE_DISTANCE {
                polygon.push(far_start);
            }
            polygon.extend_from_slice(&self.points);
            polygon.push(far_end);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalises_and_closes_far_away() {
        let points = [DVec3::ZERO, DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)];
        let curve = NormalisedCurve::new(&points).expect("non-degenerate");
        assert_eq!(curve.as_closed_polygon().len(), 3);
        let loop_points = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ZERO];
        let closed = NormalisedCurve::new(&loop_points).expect("non-degenerate");
        assert_eq!(closed.as_closed_polygon().len(), 3);
        let mut polygon = Vec::new();
        curve.close(DVec3::Z, &mut polygon);
        assert_eq!(polygon.len(), 5);
        assert!((polygon[0].z - CLOSURE_DISTANCE).abs() < 1e-12);
        assert!((polygon[4].z - CLOSURE_DISTANCE).abs() < 1e-12);
        assert!(matches!(
            NormalisedCurve::new(&[DVec3::ONE; 4]),
            Err(KnotError::DegenerateExtent { .. })
        ));
    }
}
