//! The body's shape at t = 0, when it is not straight: an open (2, q) torus knot (a trefoil
//! for q = 3, a cinquefoil for q = 5), for starting a rod already knotted (the loose knots of
//! rod theory, `docs/validation.md`), or a curve read from a file of vertices
//! ([`PolylineShape`]: another simulator's starting knot).
//!
//! The chain is posed by its bending joints ([`hagfish_tree::pose_along`]); the twist joints
//! stay at 0.

use glam::{DMat3, DVec3};
use hagfish_tree::{Model, pose_along};
use serde::{Deserialize, Serialize};

use crate::polyline_shape::PolylineShape;

/// The body's shape at t = 0 (the default, no shape, is straight along +X from the head).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum InitialShape {
    /// An open torus knot ([`OpenTorusKnot`]).
    OpenTorusKnot(OpenTorusKnot),
    /// A curve read from a file of vertices ([`PolylineShape`]).
    Polyline(PolylineShape),
}

/// An open (2, q) torus knot: the head runs straight along +X for `start_l`·L, then the body
/// follows the closed knot `c(t) = ((R₀ + a cos qt) cos 2t, (R₀ + a cos qt) sin 2t,
/// ±a sin qt)`, `a = R₀/2`, from t = 0 to 2π, and leaves it along a straight line parallel to
/// the head line. The closed knot is cut open at t = 0 (its point farthest from the torus
/// axis, where the lines in and out are tangent to it and stay outside the torus): the
/// strands near the cut are pushed apart by ±ε·b, `ε = 0.3a`, `b = c′(0) × c(0)` normalised,
/// with Gaussian weights `exp(−(t/σ)²)` and `exp(−((2π − t)/σ)²)`, `σ = 0.3`, so the lines
/// in and out join it without a kink and pass each other 2ε apart. Closed far away, the curve
/// is the (2, q) torus knot, so the knot type is exact; the whole is turned so that the lines
/// run along +X.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OpenTorusKnot {
    /// q, odd and at least 3: 3 is the trefoil 3₁, 5 the cinquefoil 5₁.
    pub crossings: u32,
    /// The torus' major radius R₀ as a fraction of the body length L (its minor radius is
    /// R₀/2).
    pub radius_l: f64,
    /// Length of the straight head part before the knot, a fraction of L; at least
    /// 3 (R₀ + a)/L so that the knot stays off the wall.
    pub start_l: f64,
    /// The mirror image (z → −z).
    #[serde(default)]
    pub mirror: bool,
}

/// The strands' separation at the cut, as a fraction of the minor radius a (each moves by ε).
const SEPARATION: f64 = 0.3;
/// Width σ (in t) of the Gaussian weights that separate the strands at the cut.
const SPREAD: f64 = 0.3;
/// Samples of the knotted part of the curve.
const SAMPLES: usize = 20_000;

impl OpenTorusKnot {
    /// The torus' major and minor radii (cm) on a body of length `length_cm`.
    fn radii(&self, length_cm: f64) -> (f64, f64) {
        let major = self.radius_l * length_cm;
        (major, 0.5 * major)
    }

    /// The smallest straight head part (fraction of L) that keeps the knot off the wall.
    pub fn min_start_l(&self) -> f64 {
        let (major, minor) = self.radii(1.0);
        3.0 * (major + minor)
    }

    /// The closed knot at parameter `t`, in the knot's own frame (torus axis +Z).
    fn closed(&self, t: f64, length_cm: f64) -> DVec3 {
        let (major, minor) = self.radii(length_cm);
        let q = f64::from(self.crossings);
        let z = if self.mirror { -1.0 } else { 1.0 };
        let r = major + minor * (q * t).cos();
        DVec3::new(r * (2.0 * t).cos(), r * (2.0 * t).sin(), z * minor * (q * t).sin())
    }

    /// The knot cut open at t = 0 (see [`OpenTorusKnot`]), in the knot's frame.
    fn opened(&self, t: f64, length_cm: f64) -> DVec3 {
        let (_, minor) = self.radii(length_cm);
        let weight = |u: f64| (-(u / SPREAD).powi(2)).exp();
        let tau = std::f64::consts::TAU;
        let p0 = self.closed(0.0, length_cm);
        let dt = 1e-6;
        let tangent = self.closed(dt, length_cm) - self.closed(-dt, length_cm);
        let apart = tangent.cross(p0).normalize();
        self.closed(t, length_cm) + SEPARATION * minor * (weight(t) - weight(tau - t)) * apart
    }

    /// The curve the body is laid along, from the head: the head line, the knot (sampled),
    /// and the tail line, ended 2L further on (world frame, cm).
    fn curve(&self, length_cm: f64) -> Vec<DVec3> {
        let tau = std::f64::consts::TAU;
        let dt = 1e-6;
        let along = (self.opened(dt, length_cm) - self.opened(-dt, length_cm)).normalize();
        // Turn `along` onto +X and put the knot's entry at (start_l·L, 0, 0).
        let side = DVec3::Z.cross(along).normalize();
        let up = along.cross(side);
        let to_world = DMat3::from_cols(along, side, up).transpose();
        let entry = self.opened(0.0, length_cm);
        let head_line = DVec3::new(self.start_l * length_cm, 0.0, 0.0);
        let mut points = vec![DVec3::ZERO];
        points.extend((0..=SAMPLES).map(|k| {
            let t = tau * k as f64 / SAMPLES as f64;
            head_line + to_world * (self.opened(t, length_cm) - entry)
        }));
        let exit = points[points.len() - 1];
        points.push(exit + DVec3::X * (2.0 * length_cm));
        points
    }

    /// Arc length of the head line and the knot (cm): the body must be longer.
    pub fn knotted_length_cm(&self, length_cm: f64) -> f64 {
        let points = self.curve(length_cm);
        let knot = &points[..points.len() - 1];
        knot.windows(2).map(|w| w[0].distance(w[1])).sum()
    }
}

impl InitialShape {
    /// The joint angles that lay `model` (a chain along +X from the head, with twist and
    /// bending joints, of total length `length_cm`) along this shape
    /// ([`hagfish_tree::pose_along`]).
    pub fn pose(&self, model: &Model, length_cm: f64) -> Vec<f64> {
        let points = match self {
            InitialShape::OpenTorusKnot(knot) => knot.curve(length_cm),
            InitialShape::Polyline(polyline) => polyline.curve(length_cm),
        };
        let mut q = vec![0.0; model.dof_count()];
        pose_along(model, &points, &mut q);
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hagfish_anatomy::{Body, Rod};
    use hagfish_knots::{KnotOptions, analyse_knot};
    use hagfish_tree::{Data, position_kinematics};

    fn rod() -> Rod {
        Rod {
            name: "test".into(),
            length_cm: 60.0,
            radius_cm: 0.02,
            body_count: 400,
            density_g_per_cm3: 1.0,
            bending_stiffness_dyn_cm2: 100.0,
            twist_stiffness_dyn_cm2: 66.7,
            damping_dyn_cm2_s: 1.0,
        }
    }

    fn knot(crossings: u32, mirror: bool) -> OpenTorusKnot {
        OpenTorusKnot { crossings, radius_l: 0.025, start_l: 0.15, mirror }
    }

    /// The joint positions of the rod posed along `knot`.
    fn posed(knot: OpenTorusKnot) -> (Vec<DVec3>, Vec<DVec3>) {
        let model = Body::Rod(rod()).to_model().expect("a model");
        let q = InitialShape::OpenTorusKnot(knot).pose(&model, 60.0);
        let mut data = Data::new(&model);
        position_kinematics(&model, &q, &mut data);
        let joints = data.joint_frames.iter().map(|f| f.translation).collect();
        let centres = (0..model.body_count()).map(|i| data.body_centre(i)).collect();
        (joints, centres)
    }

    #[test]
    fn every_bending_joint_of_the_posed_chain_lies_on_the_curve() {
        let shape = knot(3, false);
        let curve = shape.curve(60.0);
        let (joints, _) = posed(shape);
        // Distance to the polyline, by its vertices and the segments between them.
        let distance = |p: DVec3| {
            curve
                .windows(2)
                .map(|w| {
                    let (a, b) = (w[0], w[1]);
                    let s = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                    p.distance(a.lerp(b, s))
                })
                .fold(f64::INFINITY, f64::min)
        };
        for (j, joint) in joints.iter().enumerate().filter(|(j, _)| j % 2 == 1) {
            assert!(distance(*joint) < 1e-9, "joint {j} is {} cm off", distance(*joint));
        }
        assert!(joints[0].length() < 1e-12 && joints[1].distance(DVec3::X * 0.15) < 1e-12);
    }

    #[test]
    fn the_posed_chain_is_the_asked_torus_knot_in_either_handedness() {
        for (crossings, name) in [(3, "3_1"), (5, "5_1")] {
            let mut writhes = Vec::new();
            for mirror in [false, true] {
                let (_, centres) = posed(knot(crossings, mirror));
                let report = analyse_knot(&centres, &KnotOptions::default()).expect("analysed");
                assert_eq!(report.knot.to_string(), name, "mirror {mirror}");
                assert!(report.agreement > 0.99, "agreement {}", report.agreement);
                writhes.push(report.writhe.expect("a knotted core has a writhe"));
            }
            assert!(writhes[0] * writhes[1] < 0.0, "{name}: writhes {writhes:?}");
        }
    }

    #[test]
    fn the_knot_starts_where_asked_and_keeps_off_the_wall() {
        let shape = knot(3, false);
        let curve = shape.curve(60.0);
        assert!(curve[1].distance(DVec3::new(9.0, 0.0, 0.0)) < 1e-12, "entry {:?}", curve[1]);
        assert!(curve.iter().all(|p| p.x > 0.0 || p.length() < 1e-12));
        assert!(shape.knotted_length_cm(60.0) < 60.0);
    }
}
