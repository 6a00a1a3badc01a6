//! Where the knot sits along an open curve.
//!
//! The extent is the smallest sub-arc [i, j] that, closed on its own like the whole curve
//! (normalised, closed at infinity, majority vote), still has the curve's knot type. It is
//! found by shrinking one end at a time with a binary search, which assumes that cutting
//! more off an end never makes a lost knot reappear — true for a knot tied in an otherwise
//! untangled strand. Each end costs ⌈log₂ n⌉ votes.

use glam::DVec3;

use crate::AlexanderPolynomial;
use crate::analysis::MIN_OPEN_POINTS;
use crate::closure::NormalisedCurve;
use crate::vote::{Workspace, elects};

/// First and last vertex index of the smallest sub-arc of `points` whose closure still has
/// polynomial `target`, voting with `directions` directions per candidate sub-arc.
pub(crate) fn knotted_extent(
    points: &[DVec3],
    target: &AlexanderPolynomial,
    directions: usize,
    workspace: &mut Workspace,
) -> (usize, usize) {
    let n = points.len();
    let mut knotted = |i: usize, j: usize| {
        NormalisedCurve::new(&points[i..=j])
            .is_ok_and(|curve| elects(&curve, directions, target, workspace))
    };
    // Largest start i with [i, n − 1] knotted; i = n − 3 leaves too few points.
    let (mut knotted_start, mut lost_start) = (0, n + 1 - MIN_OPEN_POINTS);
    while lost_start - knotted_start > 1 {
        let mid = knotted_start + (lost_start - knotted_start) / 2;
        if knotted(mid, n - 1) {
            knotted_start = mid;
        } else {
            lost_start = mid;
        }
    }
    // Smallest end j with [start, j] knotted; j = start + 2 leaves too few points.
    let (mut lost_end, mut knotted_end) = (knotted_start + MIN_OPEN_POINTS - 2, n - 1);
    while knotted_end - lost_end > 1 {
        let mid = lost_end + (knotted_end - lost_end) / 2;
        if knotted(knotted_start, mid) {
            knotted_end = mid;
        } else {
            lost_end = mid;
        }
    }
    (knotted_start, knotted_end)
}

/// Arc length along `points` from vertex 0 to the midpoint (in arc length) of the sub-arc
/// [`first`, `last`]: (s(first) + s(last)) / 2 with s(k) = Σ_{l<k} |p_{l+1} − p_l|.
pub(crate) fn midpoint_arc_length(points: &[DVec3], first: usize, last: usize) -> f64 {
    let arc_length = |k: usize| points[..=k].windows(2).map(|w| w[0].distance(w[1])).sum::<f64>();
    0.5 * (arc_length(first) + arc_length(last))
}
