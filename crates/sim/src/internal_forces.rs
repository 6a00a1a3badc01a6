//! Stage `internal_forces`: the load each joint transmits during the step (`docs/physics.md`,
//! "Internal forces"), from the step's constraint and applied forces by a backward pass over
//! the tree ([`hagfish_tree::joint_wrenches`]).
//!
//! Self-contact, wall and thigmotaxis rows push on body centres: a row with coefficient
//! `dᵀ Σ_m s_m w_m P_m` (direction d, spline weights w_m, sign s_m = ±1 for the two strands)
//! and impulse λ exerts the force `s_m w_m (λ/h) d` at centre m. A grip's rows exert their
//! force at the gripped point and their moment on its body. Head and limit rows act in
//! joint space and show up as the joints' torques. The result, per joint j, is the force and
//! moment that the distal part (the subtree) exerts on the proximal part, in the frame of
//! body j (x along the body): the rod's internal force n and moment m at the joint.

use crate::rows::RowGroup;
use glam::DVec3;
use hagfish_geometry::SplineWeights;
use hagfish_tree::{Model, Spatial, State};

use crate::options::StepOptions;
use crate::rows::{
    Friction, MAX_FRICTION_EDGES, contact_directions, grip_wrench, thigmo_strands,
    wall_contact_offset,
};
use crate::step_data::StepData;

/// The internal load at one joint: the force (dyn) and moment (dyn·cm) that the part of the
/// body beyond the joint (tail-ward) exerts on the part before it, in the frame of the body
/// that follows the joint (x along the body, the twist axis). Positive tension pulls the
/// two parts apart.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointLoad {
    /// Axial force N = n·t (dyn), > 0 in tension.
    pub tension_dyn: f64,
    /// Shear force along the body's y axis (dyn).
    pub shear_y_dyn: f64,
    /// Shear force along the body's z axis (dyn).
    pub shear_z_dyn: f64,
    /// Twisting moment m·t (dyn·cm).
    pub twist_dyn_cm: f64,
    /// Bending moment about the body's y axis (dyn·cm).
    pub bend_y_dyn_cm: f64,
    /// Bending moment about the body's z axis (dyn·cm).
    pub bend_z_dyn_cm: f64,
}

impl JointLoad {
    /// The magnitude of the bending moment `√(m_y² + m_z²)` (dyn·cm).
    pub fn bending_dyn_cm(&self) -> f64 {
        self.bend_y_dyn_cm.hypot(self.bend_z_dyn_cm)
    }
}

/// Buffers of the stage, allocated once per world.
#[derive(Clone, Debug, Default)]
pub struct InternalForces {
    /// Constraint wrenches on each body from self-contact, wall and thigmotaxis rows (world,
    /// at the origin).
    external: Vec<Spatial>,
    /// The wrench each joint's parent exerts on its subtree (world, at the origin).
    wrenches: Vec<Spatial>,
    /// The loads of the last step, one per joint, head first.
    pub loads: Vec<JointLoad>,
    /// The grip's pull in the last step, when a grip held the tail end.
    pub grip: Option<GripLoad>,
}

/// What a grip ([`hagfish_control::Grip`]) did in a step: where it held its body and the force
/// its rows exerted there, F = Σ λ_k e_k / h over its three force rows.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GripLoad {
    /// The gripped point (cm, world).
    pub point: DVec3,
    /// The force on the body at that point (dyn, world).
    pub force: DVec3,
}

impl InternalForces {
    /// Buffers for `bodies` joints.
    pub fn new(bodies: usize) -> Self {
        Self {
            external: vec![Spatial::ZERO; bodies],
            wrenches: vec![Spatial::ZERO; bodies],
            loads: vec![JointLoad::default(); bodies],
            grip: None,
        }
    }
}

/// Stage 6d (after the last solve, before `integrate`): fills `data.internal.loads` for the
/// step from `state` (still the step's start) to the solved velocities.
pub fn internal_forces(model: &Model, options: &StepOptions, state: &State, data: &mut StepData) {
    let h = options.time_step;
    collect_row_wrenches(data, h, options.friction);
    let internal = &mut data.internal;
    hagfish_tree::joint_wrenches(
        model,
        &mut data.tree,
        &state.qdot,
        data.solver.velocity(),
        h,
        &internal.external,
        &mut internal.wrenches,
    );
    for (j, (load, w)) in internal.loads.iter_mut().zip(&internal.wrenches).enumerate() {
        let frame = &data.tree.joint_frames[j];
        let rt = frame.rotation.transpose();
        // The subtree's action on the parent is −W; its moment about the joint point p is
        // −(n_O − p × f).
        let force = rt * -w.linear;
        let moment = rt * -(w.angular - frame.translation.cross(w.linear));
        *load = JointLoad {
            tension_dyn: force.x,
            shear_y_dyn: force.y,
            shear_z_dyn: force.z,
            twist_dyn_cm: moment.x,
            bend_y_dyn_cm: moment.y,
            bend_z_dyn_cm: moment.z,
        };
    }
}

/// Sums the forces of the self-contact, wall and thigmotaxis rows on the body centres into
/// `data.internal.external`, each row's object found by its source id (a wall or self
/// contact, a thigmotaxis request and its contact). With `friction` a contact's consecutive
/// rows push along its pyramid's edges, in the order `rows::contact_directions` gives them,
/// and a wall contact's at its contact point.
fn collect_row_wrenches(data: &mut StepData, h: f64, friction: Option<Friction>) {
    let external = &mut data.internal.external;
    external.fill(Spatial::ZERO);
    let centres = &data.centres;
    let mut push =
        |weights: &SplineWeights, sign: f64, (direction, offset): (DVec3, DVec3), force: f64| {
            for (body, w) in weights.iter() {
                // The centre itself, bit for bit, where there is no offset.
                let at = if offset == DVec3::ZERO { centres[body] } else { centres[body] + offset };
                external[body] += Spatial::point_force(at, direction * (sign * w * force));
            }
        };
    let (contacts, requests) = (&data.self_contacts, &data.actuation.thigmo);
    let multipliers = data.solver.multipliers();
    let mut directions = [DVec3::ZERO; MAX_FRICTION_EDGES];
    // The contact whose rows are being read, its number of edges, and the row's among them.
    let (mut current, mut edges, mut edge) = (None, 1, 0);
    for (source, &lambda) in data.rows.sources().iter().zip(multipliers) {
        let force = lambda / h;
        let group = RowGroup::of(source.tag);
        if current == Some((source.tag, source.id)) {
            edge += 1;
        } else {
            (current, edge) = (Some((source.tag, source.id)), 0);
        }
        match group {
            Some(RowGroup::Wall) => {
                if let Some(c) = data.wall_contacts.get(source.id) {
                    if edge == 0 {
                        edges = contact_directions(c.normal, DVec3::X, friction, &mut directions);
                    }
                    let offset = wall_contact_offset(edges, c.radius, c.normal);
                    let along = (directions[edge.min(edges - 1)], offset);
                    push(&c.weights, 1.0, along, force);
                }
            }
            Some(RowGroup::Contact) => {
                if let Some(c) = contacts.get(source.id) {
                    if edge == 0 {
                        edges =
                            contact_directions(c.normal, c.tangent_a, friction, &mut directions);
                    }
                    let along = (directions[edge.min(edges - 1)], DVec3::ZERO);
                    push(&c.weights_b, 1.0, along, force);
                    push(&c.weights_a, -1.0, along, force);
                }
            }
            Some(RowGroup::Skin) => {
                if let Some(c) = contacts.get(source.id) {
                    push(&c.weights_b, 1.0, (c.normal, DVec3::ZERO), force);
                    push(&c.weights_a, -1.0, (c.normal, DVec3::ZERO), force);
                }
            }
            Some(RowGroup::Thigmo) => {
                let request = requests.get(source.id);
                let strands = request.and_then(|r| contacts.get(r.contact).map(|c| (r, c)));
                if let Some((this, other, tangent)) = strands.map(|(r, c)| thigmo_strands(r, c)) {
                    push(this, 1.0, (tangent, DVec3::ZERO), force);
                    push(other, -1.0, (tangent, DVec3::ZERO), force);
                }
            }
            Some(RowGroup::Head | RowGroup::Limit | RowGroup::Grip) | None => {}
        }
    }
    data.internal.grip = data.actuation.grip.as_ref().map(|grip| {
        let (force, moment) = grip_wrench(&data.rows, multipliers, h);
        external[grip.body] +=
            Spatial::point_force(grip.point, force) + Spatial::new(moment, DVec3::ZERO);
        GripLoad { point: grip.point, force }
    });
}
