//! Stage 1, forward kinematics: frames, world axes, twists and velocity-product accelerations.
//!
//! One root-to-leaf pass. For joint `i` with parent `p`, starting from `F = E_wj,p · E⁰_pj,i`,
//! each DOF `a` of the joint in turn contributes the world axis `s_a = (R_F e_a; p_F × R_F e_a)`
//! (a rotation about the line through the joint origin), its rate `ṡ_a = V_F ×ₘ s_a` where
//! `V_F` is the twist of the frame the axis is fixed in, and then rotates the frame:
//! `F ← F · Rot(e_a, q_a)`. Twists add along the path: `V_i = V_p + Σ s_a q̇_a`, and so do
//! the velocity-product accelerations `A_i = A_p + Σ ṡ_a q̇_a`.

use crate::data::Data;
use crate::model::Model;
use crate::spatial::{RigidInertia, Spatial, Transform};

/// Fills `joint_frames`, `body_frames`, `axes` (and `axis_components`), `axis_rates`, `velocities`,
/// `bias_accelerations` and `inertias` of `data` for the configuration `q` and rates `qdot`.
/// The lengths of `q` and `qdot` must equal `model.dof_count()` (see [`crate::State::validate`]).
pub fn forward_kinematics(model: &Model, q: &[f64], qdot: &[f64], data: &mut Data) {
    for (i, joint) in model.joints().iter().enumerate() {
        let (parent_frame, mut twist, mut accel) = match joint.parent {
            Some(p) => (data.joint_frames[p], data.velocities[p], data.bias_accelerations[p]),
            None => (Transform::IDENTITY, Spatial::ZERO, Spatial::ZERO),
        };
        let mut frame = parent_frame.mul(&joint.offset);
        for (k, a) in joint.dofs().enumerate() {
            let local_axis = joint.kind.axis(k);
            let axis = Spatial::revolute_axis(frame.rotation * local_axis, frame.translation);
            let rate = twist.cross_motion(&axis);
            data.axes[a] = axis;
            data.axis_rates[a] = rate;
            twist = twist.add_scaled(&axis, qdot[a]);
            accel = accel.add_scaled(&rate, qdot[a]);
            frame = frame.mul(&Transform::from_axis_angle(local_axis, q[a]));
        }
        let body = &model.bodies()[i];
        let body_frame = frame.mul(&body.offset);
        data.joint_frames[i] = frame;
        data.body_frames[i] = body_frame;
        data.velocities[i] = twist;
        data.bias_accelerations[i] = accel;
        data.inertias[i] = RigidInertia::from_body(body.mass, body.principal_inertia, &body_frame);
    }
    data.axis_components.fill_from(&data.axes);
}
