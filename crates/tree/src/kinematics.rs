//! Stage 1, forward kinematics: frames, world axes, twists and velocity-product accelerations.
//!
//! One root-to-leaf pass. For joint `i` with parent `p`, starting from `F = E_wj,p · E⁰_pj,i`,
//! each DOF `a` of the joint in turn contributes the world axis `s_a = (R_F e_a; p_F × R_F e_a)`
//! (a rotation about the line through the joint origin), its rate `ṡ_a = V_F ×ₘ s_a` where
//! `V_F` is the twist of the frame the axis is fixed in, and then rotates the frame:
//! `F ← F · Rot(e_a, q_a)`. A translation DOF has `s_a = (0; R_F e_a)` and moves the frame:
//! `p_F ← p_F + q_a R_F e_a`. Twists add along the path: `V_i = V_p + Σ s_a q̇_a`, and so do
//! the velocity-product accelerations `A_i = A_p + Σ ṡ_a q̇_a`.

use crate::data::Data;
use crate::model::Model;
use crate::spatial::{RigidInertia, Spatial, Transform};

/// Fills `joint_frames`, `body_frames`, `axes` (and `axis_components`), `axis_rates`,
/// `velocities`, `bias_accelerations` and `inertias` of `data` for the configuration `q` and
/// rates `qdot`.
/// The lengths of `q` and `qdot` must equal `model.dof_count()` (see [`crate::State::validate`]).
pub fn forward_kinematics(model: &Model, q: &[f64], qdot: &[f64], data: &mut Data) {
    position_kinematics(model, q, data);
    velocity_kinematics(model, qdot, data);
}

/// The configuration half of [`forward_kinematics`]: `joint_frames`, `body_frames`, `axes`
/// (and `axis_components`) and `inertias` for `q`; enough for positions (such as
/// [`Data::body_centre`]) where no velocity is needed.
pub fn position_kinematics(model: &Model, q: &[f64], data: &mut Data) {
    frame_kinematics(model, q, data);
    for ((inertia, body), frame) in
        data.inertias.iter_mut().zip(model.bodies()).zip(&data.body_frames)
    {
        *inertia = RigidInertia::from_body(body.mass, body.principal_inertia, frame);
    }
    data.axis_components.fill_from(&data.axes);
}

/// The frames of [`position_kinematics`] alone: `joint_frames`, `body_frames` and `axes` for
/// `q`, without the bodies' spatial inertias: for body positions only (the contact
/// predictor's centreline at `q + h q̇`).
pub fn frame_kinematics(model: &Model, q: &[f64], data: &mut Data) {
    for (i, joint) in model.joints().iter().enumerate() {
        let parent_frame = joint.parent.map_or(Transform::IDENTITY, |p| data.joint_frames[p]);
        let mut frame = parent_frame.mul(&joint.offset);
        for (k, a) in joint.dofs().enumerate() {
            let local_axis = joint.kind.axis(k);
            let world_axis = frame.rotation * local_axis;
            if joint.kind.translates() {
                data.axes[a] = Spatial::prismatic_axis(world_axis);
                frame.translation += world_axis * q[a];
            } else {
                data.axes[a] = Spatial::revolute_axis(world_axis, frame.translation);
                frame = frame.rotated(local_axis, q[a]);
            }
        }
        data.joint_frames[i] = frame;
        data.body_frames[i] = frame.mul(&model.bodies()[i].offset);
    }
}

/// The rate half of [`forward_kinematics`]: `axis_rates`, `velocities` and
/// `bias_accelerations` for the rates `qdot`, from the `axes` already in `data`. Re-evaluates
/// the velocity products at new rates when the configuration has not changed since the last
/// [`forward_kinematics`] (the same numbers as calling it again, without the frames).
pub fn velocity_kinematics(model: &Model, qdot: &[f64], data: &mut Data) {
    for (i, joint) in model.joints().iter().enumerate() {
        let (mut twist, mut accel) = match joint.parent {
            Some(p) => (data.velocities[p], data.bias_accelerations[p]),
            None => (Spatial::ZERO, Spatial::ZERO),
        };
        for a in joint.dofs() {
            let axis = data.axes[a];
            let rate = twist.cross_motion(&axis);
            data.axis_rates[a] = rate;
            twist = twist.add_scaled(&axis, qdot[a]);
            accel = accel.add_scaled(&rate, qdot[a]);
        }
        data.velocities[i] = twist;
        data.bias_accelerations[i] = accel;
    }
}
