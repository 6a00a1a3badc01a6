//! How much tube a body is: its length in local diameters D = 2r.
//!
//! A knot in a tube needs a length of tube (ideal closed knots: trefoil ≈ 16.4 D,
//! figure-eight ≈ 21 D), so a plan laid out in fractions of the body length L makes a
//! tighter knot with less tail beyond it on a shorter or thicker body. These measures let a
//! tie keep the tube it plans with ([`crate::TiePhase::min_tail_d`]).

use hagfish_tree::Body;

/// Local diameters of body tail-ward of the fraction `at` of the body length from the head:
/// ∫ ds / 2r(s) from `at`·L to L, each body a cylinder of its radius (so the integral is a
/// sum of ℓ/2r, with the part of the body that `at` falls in).
pub fn diameters_tail_ward(bodies: &[Body], at: f64) -> f64 {
    let from = at * bodies.iter().map(|b| b.length).sum::<f64>();
    let mut start = 0.0;
    let mut diameters = 0.0;
    for body in bodies {
        let end = start + body.length;
        diameters += (end - start.max(from)).max(0.0) / (2.0 * body.radius);
        start = end;
    }
    diameters
}

/// The fraction a of the body length from the head that leaves `diameters` local diameters
/// of body tail-ward of it: the inverse of [`diameters_tail_ward`]; 0 (the head) when the
/// whole body is shorter.
pub fn fraction_leaving(bodies: &[Body], diameters: f64) -> f64 {
    let length: f64 = bodies.iter().map(|b| b.length).sum();
    let mut end = length;
    let mut left = diameters;
    for body in bodies.iter().rev() {
        let whole = body.length / (2.0 * body.radius);
        if whole >= left {
            return (end - left * 2.0 * body.radius) / length;
        }
        left -= whole;
        end -= body.length;
    }
    0.0
}

/// A cylinder of `length` and `radius` (cm) as a tree body, for tests of body measures.
#[cfg(test)]
pub(crate) fn cylinder(length: f64, radius: f64) -> Body {
    Body {
        mass: 1.0,
        principal_inertia: glam::DVec3::ONE,
        offset: hagfish_tree::Transform::IDENTITY,
        radius,
        length,
        skin: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_tube_is_its_length_over_its_diameter() {
        let tube = vec![cylinder(0.5, 0.25); 40];
        assert!((diameters_tail_ward(&tube, 0.0) - 40.0).abs() < 1e-12);
        assert!((diameters_tail_ward(&tube, 0.3) - 28.0).abs() < 1e-12);
        assert!((diameters_tail_ward(&tube, 1.0)).abs() < 1e-12);
        assert!((fraction_leaving(&tube, 28.0) - 0.3).abs() < 1e-12);
        assert_eq!(fraction_leaving(&tube, 41.0), 0.0, "longer than the body: the head");
    }

    /// On a tapering body the fraction that leaves d diameters is where d are left, to
    /// rounding, inside a body as well as at its ends.
    #[test]
    fn the_fraction_leaving_inverts_the_diameters_on_a_taper() {
        let taper: Vec<Body> =
            (0..30).map(|k| cylinder(0.4 + 0.01 * k as f64, 1.0 - 0.02 * k as f64)).collect();
        let total = diameters_tail_ward(&taper, 0.0);
        for d in [0.1, 1.0, 3.7, 10.0, total * 0.5, total - 1e-9] {
            let at = fraction_leaving(&taper, d);
            assert!((diameters_tail_ward(&taper, at) - d).abs() < 1e-9, "{d} diameters at {at}");
        }
        assert!(
            fraction_leaving(&taper, 5.0) > fraction_leaving(&taper, 6.0),
            "more tube, nearer the head"
        );
    }
}
