//! Closest points of two straight line segments, in closed form.
//!
//! The narrow phase starts its Newton iteration from the closest points of the two
//! chords c_k → c_{k+1}, which are already close to the spline's closest points for the
//! gently bent body (a better start than the thesis' s = 0.5: from the middle, Newton can run to a
//! maximum or a saddle of the distance, see `narrow_phase.rs`).

use glam::DVec3;

/// Squared length (cm²) under which a chord is treated as a point.
const DEGENERATE_LENGTH_SQUARED: f64 = 1e-24;

/// Relative size of 1 − cos²θ under which two chords are treated as parallel.
const PARALLEL_TOLERANCE: f64 = 1e-12;

/// Parameters [s, t] ∈ [0, 1]² of the closest points p₀ + s(p₁ − p₀) and q₀ + t(q₁ − q₀)
/// of the segments p₀p₁ and q₀q₁.
///
/// Minimises |p(s) − q(t)|² over the unit square: the unconstrained minimiser
/// s = (b f − c e)/(a e − b²) (a = d₁·d₁, b = d₁·d₂, c = d₁·r, e = d₂·d₂, f = d₂·r,
/// d₁ = p₁ − p₀, d₂ = q₁ − q₀, r = p₀ − q₀) is clamped, then t = (b s + f)/e is clamped and
/// s recomputed for the clamped t. Parallel chords take s = 0; degenerate (point) chords
/// are handled explicitly.
pub(crate) fn closest_chord_parameters(p: (DVec3, DVec3), q: (DVec3, DVec3)) -> [f64; 2] {
    let d1 = p.1 - p.0;
    let d2 = q.1 - q.0;
    let r = p.0 - q.0;
    let a = d1.length_squared();
    let e = d2.length_squared();
    let f = d2.dot(r);
    if a <= DEGENERATE_LENGTH_SQUARED && e <= DEGENERATE_LENGTH_SQUARED {
        return [0.0, 0.0];
    }
    if a <= DEGENERATE_LENGTH_SQUARED {
        return [0.0, (f / e).clamp(0.0, 1.0)];
    }
    let c = d1.dot(r);
    if e <= DEGENERATE_LENGTH_SQUARED {
        return [(-c / a).clamp(0.0, 1.0), 0.0];
    }
    let b = d1.dot(d2);
    let denominator = a * e - b * b;
    let s = if denominator > PARALLEL_TOLERANCE * a * e {
        ((b * f - c * e) / denominator).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let t = (b * s + f) / e;
    if t < 0.0 {
        [(-c / a).clamp(0.0, 1.0), 0.0]
    } else if t > 1.0 {
        [((b - c) / a).clamp(0.0, 1.0), 1.0]
    } else {
        [s, t]
    }
}

/// Distance (cm) between the points p₀ + s(p₁ − p₀) and q₀ + t(q₁ − q₀) of the segments
/// p₀p₁ and q₀q₁; at `[s, t]` = [`closest_chord_parameters`], the segments' distance.
pub(crate) fn chord_distance(p: (DVec3, DVec3), q: (DVec3, DVec3), [s, t]: [f64; 2]) -> f64 {
    p.0.lerp(p.1, s).distance(q.0.lerp(q.1, t))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_chords_meet_in_their_middles() {
        let p = (DVec3::new(-1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0));
        let q = (DVec3::new(0.0, -1.0, 0.5), DVec3::new(0.0, 1.0, 0.5));
        let [s, t] = closest_chord_parameters(p, q);
        assert!((s - 0.5).abs() < 1e-15 && (t - 0.5).abs() < 1e-15);
    }

    #[test]
    fn clamps_to_end_points() {
        let p = (DVec3::ZERO, DVec3::X);
        let q = (DVec3::new(2.0, 1.0, 0.0), DVec3::new(3.0, 2.0, 0.0));
        assert_eq!(closest_chord_parameters(p, q), [1.0, 0.0]);
    }

    #[test]
    fn parallel_and_degenerate_chords_give_valid_parameters() {
        let p = (DVec3::ZERO, DVec3::X);
        let q = (DVec3::new(0.5, 1.0, 0.0), DVec3::new(1.5, 1.0, 0.0));
        assert!((chord_distance(p, q, closest_chord_parameters(p, q)) - 1.0).abs() < 1e-15);
        let point = (DVec3::new(0.3, 2.0, 0.0), DVec3::new(0.3, 2.0, 0.0));
        assert_eq!(closest_chord_parameters(p, point), [0.3, 0.0]);
        assert_eq!(closest_chord_parameters(point, p), [0.0, 0.3]);
    }
}
