//! The crossings a tail makes, seen from above: how the tie controller checks each crossing
//! as it is made.
//!
//! Project the polyline of body centres along `view` (+Z, "from above"). Every crossing of a
//! projected segment `i` with a non-adjacent earlier one `j < i − 1` has a tail-ward strand
//! (segment `i`) and a head-ward one (`j`); the tail-ward strand is [`Layer::Over`] when its
//! point of the crossing lies further along `view` than the other's. Walking from body `from`
//! to the tail lists the crossings the tail has made, in the order it made them — the
//! over/under sequence of Haney's rules (crossover, wrap, insertion; thesis §3.3.1).

use glam::{DVec2, DVec3};

use crate::loops::segment_crossing;

/// Which strand lies on top at a crossing, as seen along the view.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Layer {
    /// The tail-ward strand is on top.
    Over,
    /// The tail-ward strand is underneath.
    Under,
}

impl Layer {
    /// The other layer (the mirror image in the view direction).
    pub fn flipped(self) -> Self {
        match self {
            Layer::Over => Layer::Under,
            Layer::Under => Layer::Over,
        }
    }
}

/// One crossing of the tail's strand with the body, seen along a view: where it lies on each
/// strand (the centreline polyline's parameter, body index plus fraction — the spline
/// parameter of a [`hagfish_geometry::SelfContact`]) and which strand is on top.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// Where it lies on the tail-ward strand.
    pub tail_u: f64,
    /// Where it lies on the head-ward strand.
    pub other_u: f64,
    /// Whether the tail-ward strand is over or under.
    pub layer: Layer,
}

/// The crossings of the strand from body `from` to the tail with the whole centreline, seen
/// along `view`, in order from `from` toward the tail: where each lies on its two strands and
/// whether the tail-ward strand is over or under.
pub fn crossings_of_tail(centres: &[DVec3], from: usize, view: DVec3) -> Vec<Crossing> {
    let view = view.normalize();
    let (u, v) = view.any_orthonormal_pair();
    let project = |p: DVec3| DVec2::new(p.dot(u), p.dot(v));
    let mut found: Vec<Crossing> = Vec::new();
    for i in from..centres.len().saturating_sub(1) {
        let (a0, a1) = (centres[i], centres[i + 1]);
        for j in 0..i.saturating_sub(1) {
            let (b0, b1) = (centres[j], centres[j + 1]);
            let Some((s, t)) = segment_crossing(project(a0), project(a1), project(b0), project(b1))
            else {
                continue;
            };
            let tail_height = a0.lerp(a1, s).dot(view);
            let head_height = b0.lerp(b1, t).dot(view);
            let layer = if tail_height > head_height { Layer::Over } else { Layer::Under };
            found.push(Crossing { tail_u: i as f64 + s, other_u: j as f64 + t, layer });
        }
    }
    found.sort_by(|a, b| a.tail_u.total_cmp(&b.tail_u));
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The layers of [`crossings_of_tail`], in order.
    fn tail_crossings(centres: &[DVec3], from: usize, view: DVec3) -> Vec<Layer> {
        crossings_of_tail(centres, from, view).into_iter().map(|c| c.layer).collect()
    }

    /// A line along +X, then a curl back over (or under) it, the tail ending inside the curl.
    fn curl(height: f64) -> Vec<DVec3> {
        let mut points: Vec<DVec3> = (0..10).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        points.extend([
            DVec3::new(10.0, 2.0, 0.0),
            DVec3::new(7.0, 3.0, 0.0),
            DVec3::new(5.5, 1.0, height),
            DVec3::new(5.5, -2.0, height),
        ]);
        points
    }

    #[test]
    fn a_tail_curled_over_the_body_makes_one_over_crossing() {
        assert_eq!(tail_crossings(&curl(1.0), 0, DVec3::Z), vec![Layer::Over]);
        assert_eq!(tail_crossings(&curl(-1.0), 0, DVec3::Z), vec![Layer::Under]);
        assert_eq!(tail_crossings(&curl(1.0), 0, -DVec3::Z), vec![Layer::Under], "seen from below");
    }

    #[test]
    fn crossings_are_listed_in_the_order_the_tail_made_them() {
        // Over the body at x = 5.5, then back under it near x = 3.7.
        let mut points = curl(1.0);
        points.extend([DVec3::new(4.0, -2.0, -1.0), DVec3::new(3.5, 2.0, -1.0)]);
        assert_eq!(tail_crossings(&points, 0, DVec3::Z), vec![Layer::Over, Layer::Under]);
        // Only the crossings of segments from body `from` on are listed.
        assert_eq!(tail_crossings(&points, 14, DVec3::Z), vec![Layer::Under]);
    }

    #[test]
    fn a_crossing_says_where_it_lies_on_both_strands() {
        let crossings = crossings_of_tail(&curl(1.0), 0, DVec3::Z);
        assert_eq!(crossings.len(), 1);
        let Crossing { tail_u, other_u, layer } = crossings[0];
        // The segment from (5.5, 1) to (5.5, −2) crosses y = 0 a third of the way, over x = 5.5.
        assert!((tail_u - (12.0 + 1.0 / 3.0)).abs() < 1e-12, "{tail_u}");
        assert!((other_u - 5.5).abs() < 1e-12, "{other_u}");
        assert_eq!(layer, Layer::Over);
    }

    #[test]
    fn a_straight_body_has_no_crossing() {
        let points: Vec<DVec3> =
            (0..20).map(|i| DVec3::new(i as f64, 0.1 * i as f64, 0.0)).collect();
        assert!(tail_crossings(&points, 0, DVec3::Z).is_empty());
    }
}
