//! Loops of the centreline seen from above: where the tail should go through.
//!
//! Project the polyline of body centres along `view` (a unit vector, +Z for "from above");
//! every crossing of two non-adjacent projected segments `i` and `j > i + 1` closes the loop
//! of vertices `i + 1 ..= j`. The largest loop (by projected area, shoelace formula) is the
//! one the knot-forming script threads.

use glam::{DVec2, DVec3};

/// A closed loop of the projected centreline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedLoop {
    /// First and last body of the loop.
    pub bodies: (usize, usize),
    /// Mean of the loop's body centres (cm, 3-D).
    pub centroid: DVec3,
    /// Projected area (cm²).
    pub area: f64,
}

/// The loop of largest projected area, or `None` when the projection has no crossing.
pub fn largest_projected_loop(centres: &[DVec3], view: DVec3) -> Option<ProjectedLoop> {
    let (u, v) = view.normalize().any_orthonormal_pair();
    let project = |p: DVec3| DVec2::new(p.dot(u), p.dot(v));
    let mut best: Option<ProjectedLoop> = None;
    for i in 0..centres.len().saturating_sub(1) {
        let (a0, a1) = (project(centres[i]), project(centres[i + 1]));
        for j in i + 2..centres.len() - 1 {
            let (b0, b1) = (project(centres[j]), project(centres[j + 1]));
            if segment_crossing(a0, a1, b0, b1).is_none() {
                continue;
            }
            let loop_points = &centres[i + 1..=j];
            let area = shoelace(loop_points.iter().map(|&p| project(p))).abs();
            if best.is_none_or(|b| area > b.area) {
                let centroid = loop_points.iter().sum::<DVec3>() / loop_points.len() as f64;
                best = Some(ProjectedLoop { bodies: (i + 1, j), centroid, area });
            }
        }
    }
    best
}

fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Where two segments `a0 a1` and `b0 b1` cross properly: the parameters (s, t) of the
/// crossing point `a0 + s (a1 − a0) = b0 + t (b1 − b0)`, both in (0, 1), or `None`.
pub(crate) fn segment_crossing(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2) -> Option<(f64, f64)> {
    let d1 = cross(a1 - a0, b0 - a0);
    let d2 = cross(a1 - a0, b1 - a0);
    let d3 = cross(b1 - b0, a0 - b0);
    let d4 = cross(b1 - b0, a1 - b0);
    (d1 * d2 < 0.0 && d3 * d4 < 0.0).then(|| (d3 / (d3 - d4), d1 / (d1 - d2)))
}

fn shoelace(points: impl Iterator<Item = DVec2> + Clone) -> f64 {
    let next = points.clone().cycle().skip(1);
    0.5 * points.zip(next).map(|(p, q)| cross(p, q)).sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_curl_has_one_loop_around_its_centre() {
        // A line along +X with a full circle of radius 2 around (5, 2) in the middle.
        let mut points: Vec<DVec3> =
            (0..10).map(|i| DVec3::new(i as f64 * 0.5, 0.0, 0.0)).collect();
        for k in 1..40 {
            let a = -std::f64::consts::FRAC_PI_2 + k as f64 * std::f64::consts::TAU / 40.0;
            points.push(DVec3::new(5.0 + 2.0 * a.cos(), 2.0 + 2.0 * a.sin(), 0.1 * k as f64));
        }
        points.extend((0..10).map(|i| DVec3::new(5.0 + i as f64 * 0.5, -0.1, 4.0)));
        let found = largest_projected_loop(&points, DVec3::Z).expect("a loop");
        assert!((found.centroid.truncate() - DVec2::new(5.0, 2.0)).length() < 0.3);
        assert!((found.area - std::f64::consts::PI * 4.0).abs() < 1.5);
    }

    #[test]
    fn a_straight_line_has_no_loop() {
        let points: Vec<DVec3> = (0..20).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        assert!(largest_projected_loop(&points, DVec3::Z).is_none());
    }
}
