//! The controller interface: what a controller sees and what it may do.

use glam::{DMat3, DVec3};
use hagfish_geometry::{Centreline, SelfContact};
use hagfish_tree::{Data, Model, State};

use crate::thigmotaxis::ThigmoRequest;

/// What a controller sees at the start of a step: the model, the state, the kinematics of that
/// state (body frames and twists in `kinematics`), the centreline and the self contacts.
#[derive(Clone, Copy, Debug)]
pub struct ControlContext<'a> {
    /// The body model.
    pub model: &'a Model,
    /// The state at the start of the step.
    pub state: &'a State,
    /// Kinematics of `state` (frames, twists); dynamics fields are not valid yet.
    pub kinematics: &'a Data,
    /// The centreline through the body centres.
    pub centreline: &'a Centreline,
    /// Self contacts, sorted head to tail by their anterior parameter.
    pub self_contacts: &'a [SelfContact],
    /// The step size h (s).
    pub time_step: f64,
}

impl ControlContext<'_> {
    /// World position of the centre of `body` (cm).
    pub fn centre(&self, body: usize) -> DVec3 {
        self.kinematics.body_centre(body)
    }

    /// World velocity of the centre of `body` (cm/s).
    pub fn centre_velocity(&self, body: usize) -> DVec3 {
        self.kinematics.velocities[body].point_velocity(self.centre(body))
    }

    /// The tail end, where loads and grips act ([`tail_end`]).
    pub fn tail_end(&self) -> (usize, DVec3, DMat3) {
        tail_end(self.model, self.kinematics)
    }
}

/// The tail end of `model` posed as `kinematics` holds it, where loads and grips act: the last
/// body, the far end of its axis (`centre + (ℓ/2) x̂`, cm) and its frame's rotation.
pub fn tail_end(model: &Model, kinematics: &Data) -> (usize, DVec3, DMat3) {
    let tail = model.body_count() - 1;
    let frame = &kinematics.body_frames[tail];
    let end = frame.translation + frame.rotation.col(0) * (0.5 * model.bodies()[tail].length);
    (tail, end, frame.rotation)
}

/// A point force on a body, applied explicitly for one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointForce {
    /// The body.
    pub body: usize,
    /// World point of application (cm).
    pub point: DVec3,
    /// Force (dyn).
    pub force: DVec3,
}

/// A linear damper on a body point, `F = −c ẋ`, treated implicitly (at the new velocity).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointDamper {
    /// The body.
    pub body: usize,
    /// World point (cm).
    pub point: DVec3,
    /// Coefficient c (dyn·s/cm), ≥ 0.
    pub coefficient: f64,
}

/// A grip on a body point (`docs/physics.md`, "Pulls at prescribed speed (grip)"): six equality rows hold the point's
/// velocity at `velocity + (β/h)(target − point)` and the body's angular velocity at
/// `(β/h) rotation_error`, β the head rows' drift correction, so that the point follows its
/// target and the body keeps its orientation. The rows' multipliers are the grip's force and
/// moment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grip {
    /// The gripped body.
    pub body: usize,
    /// The gripped point, where it is (world, cm).
    pub point: DVec3,
    /// Where the point should be (world, cm).
    pub target: DVec3,
    /// The target's velocity (cm/s).
    pub velocity: DVec3,
    /// The rotation vector that turns the body back to its held orientation (world, rad).
    pub rotation_error: DVec3,
}

/// What controllers ask for in one step. Cleared by the pipeline before each step; the
/// buffers keep their capacity.
#[derive(Clone, Debug, Default)]
pub struct Actuation {
    /// Explicit point forces.
    pub forces: Vec<PointForce>,
    /// Implicit point dampers.
    pub dampers: Vec<PointDamper>,
    /// Thigmotaxis rows for the constraint solve.
    pub thigmo: Vec<ThigmoRequest>,
    /// A grip's rows for the constraint solve ([`crate::PullPhase`]), or `None`.
    pub grip: Option<Grip>,
    /// Joint torques τ_ext, one per DOF (dyn·cm), or empty for none (an open-loop replay,
    /// [`crate::Replay`]).
    pub torques: Vec<f64>,
    /// Implicit joint servo stiffness per DOF (dyn·cm/rad), or empty for none: a servo
    /// `τ = k(q* − q¹) − c(q̇¹ − q̇*)` is its explicit part `k(q* − q⁰) + c q̇*` in
    /// [`Actuation::torques`] and its gains here and in [`Actuation::servo_damping`]
    /// (`hagfish_tree::Data::servo_stiffness`; a [`crate::FollowPhase`]).
    pub servo_stiffness: Vec<f64>,
    /// Implicit joint servo damping per DOF (dyn·cm·s/rad), or empty for none.
    pub servo_damping: Vec<f64>,
}

impl Actuation {
    /// Empties every buffer.
    pub fn clear(&mut self) {
        self.forces.clear();
        self.dampers.clear();
        self.thigmo.clear();
        self.grip = None;
        self.torques.clear();
        self.servo_stiffness.clear();
        self.servo_damping.clear();
    }

    /// Writes the forces, dampers, joint torques and servos into the tree data for the dynamics
    /// stage (the thigmotaxis requests are rows, built by the pipeline).
    pub fn apply_to(&self, data: &mut Data) {
        for f in &self.forces {
            data.apply_point_force(f.body, f.point, f.force);
        }
        for d in &self.dampers {
            data.apply_point_damping(d.body, d.point, d.coefficient);
        }
        for (applied, torque) in data.applied_torques.iter_mut().zip(&self.torques) {
            *applied += torque;
        }
        for (applied, k) in data.servo_stiffness.iter_mut().zip(&self.servo_stiffness) {
            *applied += k;
        }
        for (applied, c) in data.servo_damping.iter_mut().zip(&self.servo_damping) {
            *applied += c;
        }
    }
}

/// A controller decides, once per step, the actuation from what it sees.
pub trait Controller {
    /// Adds this step's actuation to `out`.
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation);
}

/// A controller that does nothing (passive body).
#[derive(Clone, Copy, Debug, Default)]
pub struct Passive;

impl Controller for Passive {
    fn control(&mut self, _: &ControlContext<'_>, _: &mut Actuation) {}
}
