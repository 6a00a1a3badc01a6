//! The hagfish-like test curve: an overhand knot (open trefoil) tied in a 100-vertex
//! centreline with the hagfish's body spacing, tails pulled straight outward. Shared by the
//! acceptance tests and `benches/knot_type.rs` (included there by path).

use glam::DVec3;

/// Number of body centres.
pub const VERTICES: usize = 100;
/// Distance between consecutive body centres along the curve, cm.
pub const SPACING: f64 = 0.424;
/// Scale of the trefoil, cm per unit of [`trefoil`] (strand separations of ~1 cm).
const SCALE: f64 = 0.8;
/// Half-width in parameter of the arc cut out of the trefoil at its lobe tip t = π.
const CUT_HALF_WIDTH: f64 = 0.15;

/// The trefoil (sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t), t ∈ [0, 2π): its xy shadow
/// has three crossings and lobe tips of radius 3 at t = π/3, π, 5π/3.
pub fn trefoil(t: f64) -> DVec3 {
    DVec3::new(t.sin() + 2.0 * (2.0 * t).sin(), t.cos() - 2.0 * (2.0 * t).cos(), -(3.0 * t).sin())
}

/// `count` points at arc-length spacing `spacing` along the polyline `path`, starting at its
/// first point (the path must be at least (count − 1)·spacing long).
pub fn resample(path: &[DVec3], spacing: f64, count: usize) -> Vec<DVec3> {
    let mut points = Vec::with_capacity(count);
    let (mut edge, mut walked) = (0, 0.0);
    for k in 0..count {
        let target = k as f64 * spacing;
        while edge + 2 < path.len() && walked + path[edge].distance(path[edge + 1]) < target {
            walked += path[edge].distance(path[edge + 1]);
            edge += 1;
        }
        let length = path[edge].distance(path[edge + 1]);
        let u = ((target - walked) / length).clamp(0.0, 1.0);
        points.push(path[edge].lerp(path[edge + 1], u));
    }
    points
}

/// Arc length of the polyline `path`.
pub fn polyline_length(path: &[DVec3]) -> f64 {
    path.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// The hagfish-like curve (cm) and the arc length of each tail (the knot occupies the arc
/// lengths between `tail` and total − `tail`). The trefoil is cut open at its lobe tip
/// t = π; the start tail leaves the cut forward and outward, the end tail backward and
/// outward, so the tails point away from each other like a rope's pulled overhand knot.
pub fn hagfish_trefoil() -> (Vec<DVec3>, f64) {
    let (start, end) =
        (std::f64::consts::PI + CUT_HALF_WIDTH, 3.0 * std::f64::consts::PI - CUT_HALF_WIDTH);
    let arc: Vec<DVec3> =
        (0..=2000).map(|k| SCALE * trefoil(start + (end - start) * k as f64 / 2000.0)).collect();
    let tangent =
        (trefoil(std::f64::consts::PI + 1e-6) - trefoil(std::f64::consts::PI - 1e-6)).normalize();
    let outward = trefoil(std::f64::consts::PI).normalize();
    let tail = 0.5 * ((VERTICES - 1) as f64 * SPACING - polyline_length(&arc));
    let start_tail = arc[0] + tail * (tangent + 0.8 * outward).normalize();
    let end_tail = arc[arc.len() - 1] + tail * (-tangent + 0.8 * outward).normalize();
    let path: Vec<DVec3> =
        std::iter::once(start_tail).chain(arc).chain(std::iter::once(end_tail)).collect();
    (resample(&path, SPACING, VERTICES), tail)
}
