//! The closest points of a centreline near known parameters: where a contact found on one
//! centreline has moved to on a slightly different one (the contact predictor of
//! `hagfish-sim` evaluates the gap at the end of a step this way).
//!
//! One projected Newton search on the segment pair holding (u_a, u_b), started from those
//! parameters; when the result sits on an inner segment end, the search moves on to the
//! neighbouring segment (at most twice) while the distance decreases.
//! It follows one basin and is cheap (a few iterations): right for a small displacement, not
//! for finding contacts. Along two strands lying side by side the distance is flat and the
//! result can wander a body or more along them: a caller checks that it still fits the contact
//! it started from (the contact predictor compares the line between the points with the
//! contact's normal).

use crate::centreline::Centreline;
use crate::narrow_phase::{NewtonStatus, search};

/// Moves to a neighbouring segment before the search stops where it is.
const MAX_SEGMENT_MOVES: usize = 2;

/// Closest points near given parameters, as global spline parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearbyClosestPoints {
    /// Parameter of the first point.
    pub u_a: f64,
    /// Parameter of the second point.
    pub u_b: f64,
    /// |x(u_b) − x(u_a)| (cm).
    pub distance: f64,
    /// Outcome of the last Newton search.
    pub status: NewtonStatus,
}

/// The local minimum of |x(u_b) − x(u_a)| on `centreline` reached from (u_a, u_b) by
/// projected Newton searches on the segment pair holding the current parameters
/// ([`Centreline::locate`]), moving across inner segment ends (at most
/// two times) while the distance decreases.
pub fn closest_points_near(centreline: &Centreline, u_a: f64, u_b: f64) -> NearbyClosestPoints {
    let segments = centreline.segment_count();
    let ((mut k_a, s_a), (mut k_b, s_b)) = (centreline.locate(u_a), centreline.locate(u_b));
    // A parameter on an inner segment end continues on the neighbouring segment.
    let across = |k: usize, s: f64| match s {
        0.0 if k > 0 => Some((k - 1, 1.0)),
        1.0 if k + 1 < segments => Some((k + 1, 0.0)),
        _ => None,
    };
    let mut found = search(&centreline.segment(k_a), &centreline.segment(k_b), [s_a, s_b]);
    for _ in 0..MAX_SEGMENT_MOVES {
        let (next_a, next_b) = (across(k_a, found.s_a), across(k_b, found.s_b));
        if next_a.is_none() && next_b.is_none() {
            break;
        }
        let (k_a2, s_a2) = next_a.unwrap_or((k_a, found.s_a));
        let (k_b2, s_b2) = next_b.unwrap_or((k_b, found.s_b));
        let moved = search(&centreline.segment(k_a2), &centreline.segment(k_b2), [s_a2, s_b2]);
        if moved.distance_squared >= found.distance_squared {
            break;
        }
        (k_a, k_b, found) = (k_a2, k_b2, moved);
    }
    NearbyClosestPoints {
        u_a: k_a as f64 + found.s_a,
        u_b: k_b as f64 + found.s_b,
        distance: found.distance_squared.sqrt(),
        status: found.status,
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    /// Two straight strands 1 cm apart in z that cross at an angle in the x–y plane: centres
    /// of strand A along x, of strand B along a tilted line, one chain.
    fn crossing(angle: f64, offset: f64) -> Centreline {
        let mut centres: Vec<DVec3> =
            (0..20).map(|i| DVec3::new(f64::from(i) - 10.0, 0.0, 0.0)).collect();
        let direction = DVec3::new(angle.cos(), angle.sin(), 0.0);
        centres.extend(
            (0..20).map(|i| DVec3::new(offset, 0.0, 1.0) + direction * (10.0 - f64::from(i))),
        );
        Centreline::new(&centres, &vec![0.3; centres.len()]).expect("valid centreline")
    }

    #[test]
    fn follows_a_crossing_that_moved_into_the_next_segment() {
        // The crossing is at u_a = 10.25 on strand A; start in the segment before.
        let line = crossing(1.0, 0.25);
        let near = closest_points_near(&line, 9.5, 30.0);
        assert_eq!(near.status, NewtonStatus::Converged);
        assert!((near.distance - 1.0).abs() < 1e-9, "{near:?}");
        assert!((line.point(near.u_a).x - 0.25).abs() < 1e-6, "{near:?}");
    }

    #[test]
    fn agrees_with_the_full_search_on_the_segment_pair() {
        let line = crossing(0.7, 0.6);
        let near = closest_points_near(&line, 10.2, 29.7);
        let full = crate::closest_points(&line.segment(10), &line.segment(29));
        assert!((near.distance - full.distance_squared.sqrt()).abs() < 1e-9, "{near:?} {full:?}");
    }
}
