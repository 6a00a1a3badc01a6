//! Tying a knot by following the leader (docs/physics.md, "Follow-the-leader tie"): the tail's
//! tip runs along a template curve of the knot and the body follows its own path, as a
//! snake's does, so that every crossing made stays made while the next is formed.
//!
//! With the head fixed at the wall, the body cannot feed into a template fixed in space: the
//! template slides head-ward as it fills. After σ of it has been followed, the target shape is
//! the straight line from the head to x = L − σ, then the template's first σ of arc (its
//! first segment along +X, as the body), the tail's tip at its end. Joint servos hold the
//! body to that shape ([`FollowPhase::actuate`]): each joint's angle targets the angle that
//! lays the chain along the target ([`hagfish_tree::pose_along`]), with an implicit spring
//! and damper (`τ = k(q* − q¹) − c(q̇¹ − q̇*)`, `hagfish_tree::Data::servo_stiffness`), the
//! torques muscles would make. Once the whole template is followed, the shape is held until
//! the knot analysis shows the knot for `hold_s` (the phase ends) or `settle_s` has passed
//! without it (the phase fails), as a [`crate::TiePhase`] ends.

use std::path::PathBuf;
use std::sync::Arc;

use glam::{DQuat, DVec3};
use hagfish_tree::{Body, pose_along};
use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext};
use crate::tie::{Handedness, shows};
use crate::tube_length::diameters_tail_ward;

/// A knot's template: a curve in units of the tube's diameter, read from a vertex file
/// (`data/knots/templates/`, made by `bench/knot_templates.py`; docs/knot-plans.md).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KnotTemplate {
    /// The vertex file, relative to the scenario file: one vertex per line, x y z in tube
    /// diameters; lines starting with `#` are comments.
    pub file: PathBuf,
    /// The Rolfsen name the knot analysis must show for the tie to end ("6_2").
    pub knot: String,
    /// The handedness the template ties as written, checked when given (`None`: achiral, or
    /// not checked).
    #[serde(default)]
    pub handedness: Option<Handedness>,
    /// Tie the mirror image: every z negated, the handedness flipped.
    #[serde(default)]
    pub mirror: bool,
    /// Body diameters per template unit (default 1; below 1 the template is tighter than the
    /// tube's outer diameter and compresses a skin): the unit is this times the mean local
    /// diameter of the body the template ends up holding.
    #[serde(default = "one")]
    pub diameters_per_unit: f64,
    /// The vertices read from `file` (template units, mirrored when asked), their first
    /// segment turned onto +X and their first vertex at the origin; `None` until the scenario
    /// is loaded.
    #[serde(skip)]
    pub vertices: Option<Arc<Vec<DVec3>>>,
}

impl PartialEq for KnotTemplate {
    /// The same file, knot, mirror and scale.
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file
            && self.knot == other.knot
            && self.handedness == other.handedness
            && self.mirror == other.mirror
            && self.diameters_per_unit == other.diameters_per_unit
    }
}

fn one() -> f64 {
    1.0
}

impl KnotTemplate {
    /// The template's vertices as the tie follows them: `raw` (template units, as read)
    /// mirrored if asked, moved so that the first is at the origin and turned (by the smallest
    /// rotation) so that the first segment runs along +X. `None` for fewer than 2 vertices or
    /// coinciding first ones.
    pub fn placed(raw: &[DVec3], mirror: bool) -> Option<Vec<DVec3>> {
        let flip = if mirror { DVec3::new(1.0, 1.0, -1.0) } else { DVec3::ONE };
        let (&first, &second) = (raw.first()?, raw.get(1)?);
        let along = ((second - first) * flip).try_normalize()?;
        let turn = DQuat::from_rotation_arc(along, DVec3::X);
        Some(raw.iter().map(|&v| turn * ((v - first) * flip)).collect())
    }

    /// The arc length of the template (template units).
    pub fn length_units(&self) -> f64 {
        self.vertices.as_deref().map_or(0.0, |v| v.windows(2).map(|w| w[0].distance(w[1])).sum())
    }

    /// The handedness the tie must show: as written, mirrored with the template.
    pub fn shown_handedness(&self) -> Option<Handedness> {
        self.handedness.map(|h| if self.mirror { h.mirrored() } else { h })
    }

    /// Whether a knot analysis (a Rolfsen name, agreement over closure directions, the core's
    /// handedness if known) shows this template's knot, as [`crate::TieKnot::is_shown_by`]
    /// judges a plan's.
    pub fn is_shown_by(&self, name: &str, agreement: f64, right_handed: Option<bool>) -> bool {
        shows(&self.knot, self.shown_handedness(), name, agreement, right_handed)
    }
}

/// The gains of the joint servos (per DOF).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServoGains {
    /// Stiffness k (dyn·cm/rad).
    pub stiffness_dyn_cm_per_rad: f64,
    /// Damping c (dyn·cm·s/rad).
    pub damping_dyn_cm_s_per_rad: f64,
}

impl Default for ServoGains {
    /// k = 2000 dyn·cm/rad, c = 20 dyn·cm·s/rad (docs/physics.md, "Follow-the-leader tie").
    fn default() -> Self {
        Self { stiffness_dyn_cm_per_rad: 2000.0, damping_dyn_cm_s_per_rad: 20.0 }
    }
}

/// A follow-the-leader tie: the tail's tip runs along [`FollowPhase::template`] at
/// `speed_cm_s`, the body held to its path by joint servos ([`FollowPhase::actuate`];
/// docs/physics.md, "Follow-the-leader tie").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowPhase {
    /// The knot's template.
    pub template: KnotTemplate,
    /// How fast the tail's tip runs along the template (cm/s; default 2).
    #[serde(default = "default_speed")]
    pub speed_cm_s: f64,
    /// The joint servos' gains.
    #[serde(default)]
    pub servo: ServoGains,
    /// How long the knot must be shown without interruption before the phase ends (s,
    /// default 0.5).
    #[serde(default = "default_hold")]
    pub hold_s: f64,
    /// How long after the template is followed the knot may take to show before the phase
    /// fails (s, default 2).
    #[serde(default = "default_settle")]
    pub settle_s: f64,
    /// Centimetres per template unit on the body it runs on ([`FollowPhase::on_body`]); 0
    /// before.
    #[serde(skip)]
    pub cm_per_unit: f64,
}

fn default_speed() -> f64 {
    2.0
}

fn default_hold() -> f64 {
    0.5
}

fn default_settle() -> f64 {
    2.0
}

/// Scratch of the servo targets, kept so that a step does not allocate.
#[derive(Clone, Debug, Default)]
pub struct FollowScratch {
    curve: Vec<DVec3>,
    target: Vec<f64>,
    previous: Vec<f64>,
}

impl FollowPhase {
    /// This phase on a body of `bodies`: the template unit in cm, `diameters_per_unit` times
    /// the mean local diameter of the part of the body the template will hold (its last S cm,
    /// S the template's length in cm: a fixed point, found by iterating).
    pub fn on_body(&self, bodies: &[Body]) -> FollowPhase {
        let length: f64 = bodies.iter().map(|b| b.length).sum();
        let units = self.template.length_units();
        let mean_diameter = bodies.iter().map(|b| 2.0 * b.radius * b.length).sum::<f64>() / length;
        let mut unit = self.template.diameters_per_unit * mean_diameter;
        for _ in 0..20 {
            let held = (unit * units).min(length);
            let diameters = diameters_tail_ward(bodies, 1.0 - held / length);
            if diameters <= 0.0 {
                break;
            }
            unit = self.template.diameters_per_unit * held / diameters;
        }
        FollowPhase { cm_per_unit: unit, ..self.clone() }
    }

    /// The template's length on the body (cm).
    pub fn length_cm(&self) -> f64 {
        self.template.length_units() * self.cm_per_unit
    }

    /// How much of the template has been followed `elapsed` s into the phase (cm).
    pub fn followed_cm(&self, elapsed: f64) -> f64 {
        (self.speed_cm_s * elapsed).clamp(0.0, self.length_cm())
    }

    /// Whether the whole template has been followed `elapsed` s into the phase.
    pub fn followed_all(&self, elapsed: f64) -> bool {
        self.speed_cm_s * elapsed >= self.length_cm()
    }

    /// Fills `curve` with the target shape after `sigma` cm of the template (world frame,
    /// cm, from the head at the origin): the straight line to (L − σ, 0, 0), the template's
    /// first σ of arc from there, then straight on along its last direction for L.
    fn target_curve(&self, sigma: f64, length: f64, curve: &mut Vec<DVec3>) {
        curve.clear();
        curve.push(DVec3::ZERO);
        let entry = DVec3::X * (length - sigma);
        curve.push(entry);
        let Some(vertices) = self.template.vertices.as_deref() else { return };
        let mut arc = 0.0;
        let mut along = DVec3::X;
        for pair in vertices.windows(2) {
            let (a, b) = (entry + pair[0] * self.cm_per_unit, entry + pair[1] * self.cm_per_unit);
            let segment = a.distance(b);
            if segment == 0.0 {
                continue;
            }
            along = (b - a) / segment;
            if arc + segment >= sigma {
                curve.push(a + along * (sigma - arc));
                break;
            }
            curve.push(b);
            arc += segment;
        }
        let end = curve[curve.len() - 1];
        curve.push(end + along * length);
    }

    /// This step's servos `elapsed` s into the phase: each joint's target angle q* lays the
    /// chain along the target shape at the step's end, its rate q̇* is the change over the
    /// step; the explicit torque `k(q* − q⁰) + c q̇*` goes to `out.torques` and the gains to
    /// the implicit servo terms. The head's joint is left to its rows.
    pub fn actuate(
        &self,
        elapsed: f64,
        context: &ControlContext<'_>,
        scratch: &mut FollowScratch,
        out: &mut Actuation,
    ) {
        let model = context.model;
        let n = model.dof_count();
        let h = context.time_step;
        let length: f64 = model.bodies().iter().map(|b| b.length).sum();
        scratch.target.resize(n, 0.0);
        scratch.previous.resize(n, 0.0);
        self.target_curve(self.followed_cm(elapsed + h), length, &mut scratch.curve);
        pose_along(model, &scratch.curve, &mut scratch.target);
        self.target_curve(self.followed_cm(elapsed), length, &mut scratch.curve);
        pose_along(model, &scratch.curve, &mut scratch.previous);
        out.torques.resize(n, 0.0);
        out.servo_stiffness.resize(n, 0.0);
        out.servo_damping.resize(n, 0.0);
        let (k, c) = (self.servo.stiffness_dyn_cm_per_rad, self.servo.damping_dyn_cm_s_per_rad);
        for joint in model.joints().iter().filter(|j| j.parent.is_some()) {
            for a in joint.dofs() {
                let rate = (scratch.target[a] - scratch.previous[a]) / h;
                out.torques[a] += k * (scratch.target[a] - context.state.q[a]) + c * rate;
                out.servo_stiffness[a] += k;
                out.servo_damping[a] += c;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::phases::{KnotObservation, Phase, PhasedController};
    use hagfish_tree::Transform;

    /// A follow phase along three perpendicular unit sides (template units, a right-handed
    /// turn), placed.
    fn corner(cm_per_unit: f64, mirror: bool) -> FollowPhase {
        let raw = [DVec3::ZERO, DVec3::Y, DVec3::new(0.0, 1.0, 1.0), DVec3::ONE];
        let template = KnotTemplate {
            file: "corner.txt".into(),
            knot: "0_1".into(),
            handedness: Some(Handedness::Right),
            mirror,
            diameters_per_unit: 0.5,
            vertices: KnotTemplate::placed(&raw, mirror).map(Arc::new),
        };
        FollowPhase {
            template,
            speed_cm_s: 2.0,
            servo: ServoGains::default(),
            hold_s: 0.5,
            settle_s: 2.0,
            cm_per_unit,
        }
    }

    fn arc(points: &[DVec3]) -> f64 {
        points.windows(2).map(|w| w[0].distance(w[1])).sum()
    }

    #[test]
    fn the_target_is_the_straight_body_then_the_followed_part_of_the_template() {
        let phase = corner(2.0, false);
        assert!((phase.length_cm() - 6.0).abs() < 1e-12);
        let mut curve = Vec::new();
        phase.target_curve(3.0, 20.0, &mut curve);
        // Head → (17, 0, 0), then 3 cm of template (its first side along +X, 1 cm of its
        // second), then 20 cm straight on along the second side.
        assert_eq!(curve[1], DVec3::new(17.0, 0.0, 0.0));
        let followed = &curve[1..curve.len() - 1];
        assert!((arc(followed) - 3.0).abs() < 1e-12, "{followed:?}");
        let tip = followed[followed.len() - 1];
        let last = curve[curve.len() - 1];
        assert!((last.distance(tip) - 20.0).abs() < 1e-12);
        // The template turned its first side onto +X: the second side is perpendicular.
        assert!((followed[1] - followed[0]).normalize().distance(DVec3::X) < 1e-12);
        assert!((tip - followed[1]).dot(DVec3::X).abs() < 1e-12);
        // All of it once followed, and never more.
        assert_eq!(phase.followed_cm(10.0), phase.length_cm());
        assert!(phase.followed_all(3.01) && !phase.followed_all(2.99));
    }

    #[test]
    fn the_mirror_negates_the_heights_and_the_handedness() {
        let (plain, mirrored) = (corner(1.0, false), corner(1.0, true));
        let (a, b) = (plain.template.vertices.clone(), mirrored.template.vertices.clone());
        let (a, b) = (a.expect("placed"), b.expect("placed"));
        // Turned onto +X by the same rotation about z-free axes: the mirrored template is the
        // plain one reflected through a plane containing +X.
        let lengths = |v: &[DVec3]| v.iter().map(|p| p.length()).collect::<Vec<_>>();
        for (p, q) in lengths(&a).iter().zip(lengths(&b)) {
            assert!((p - q).abs() < 1e-12);
        }
        let volume = |v: &[DVec3]| (v[1] - v[0]).cross(v[2] - v[1]).dot(v[3] - v[2]);
        assert!((volume(&a) + volume(&b)).abs() < 1e-12 && volume(&a).abs() > 0.1);
        assert_eq!(mirrored.template.shown_handedness(), Some(Handedness::Left));
    }

    #[test]
    fn on_a_body_the_unit_is_the_held_parts_mean_diameter_times_the_scale() {
        let body = |radius: f64| Body {
            mass: 1.0,
            principal_inertia: DVec3::ONE,
            offset: Transform::IDENTITY,
            radius,
            length: 1.0,
            skin: None,
        };
        // 10 cm of radius 1 then 10 cm of radius 0.5: the template (3 units at 0.5 D per
        // unit) is held by the thin part, 1 cm in diameter there: 0.5 cm per unit.
        let bodies: Vec<Body> = (0..20).map(|i| body(if i < 10 { 1.0 } else { 0.5 })).collect();
        let placed = corner(0.0, false).on_body(&bodies);
        assert!((placed.cm_per_unit - 0.5).abs() < 1e-12, "{}", placed.cm_per_unit);
    }

    /// A follow-the-leader tie is judged as a tie: shown (type and handedness, mirrored with
    /// the template) it is held; not shown `settle_s` after its template it fails, once.
    #[test]
    fn a_follow_tie_ends_on_its_knot_and_fails_without_it() {
        let template = KnotTemplate {
            file: "6_2.txt".into(),
            knot: "6_2".into(),
            handedness: Some(Handedness::Right),
            mirror: true,
            diameters_per_unit: 1.0,
            vertices: None,
        };
        let follow = FollowPhase {
            template,
            speed_cm_s: 2.0,
            servo: ServoGains::default(),
            hold_s: 0.5,
            settle_s: 2.0,
            cm_per_unit: 1.0,
        };
        let mut controller = PhasedController::new(None, vec![Phase::Follow(follow)]);
        let seen = |right_handed| KnotObservation {
            name: "6_2",
            agreement: 0.95,
            right_handed: Some(right_handed),
            core_start_l: Some(0.25),
            core_length_d: Some(18.0),
        };
        controller.observe_knot(9.0, Some(seen(false)));
        assert_eq!(controller.tie.shown_since, Some(9.0), "the mirror image is left-handed");
        controller.observe_knot(9.1, Some(seen(true)));
        assert_eq!(controller.tie.shown_since, None, "the other handedness is not it");
        controller.tie.plan_done_at = Some(10.0);
        controller.observe_knot(11.9, None);
        assert!(controller.tie_failure().is_none(), "within settle_s");
        controller.observe_knot(12.0, None);
        let failure = controller.tie_failure().expect("failed after settle_s");
        assert_eq!((failure.knot.as_str(), failure.attempts), ("6_2", 1));
        assert_eq!(
            controller.unfinished_phase().as_deref(),
            Some("tie (6_2 not tied, following its template)")
        );
    }
}
