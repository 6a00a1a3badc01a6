//! The wrench each joint transmits during a step: Newton–Euler on every subtree, after the
//! velocities `q̇¹` of the step are known (the internal forces along a rod or a hagfish).
//!
//! The step solves `M̃ q̇¹ = M q̇⁰ + h f_r + Cᵀλ` with `M̃ = M + h Jᵀ C_m J + hD + h²K`. Read as
//! a balance of momentum over the step, body k feels the applied wrench `w_k`, its implicit
//! dampers at the new twist, `−C_k V¹_k`, and the external constraint wrenches `e_k` (contact
//! forces, `λ/h`); its momentum changes at the rate `I_k a_k + V_k ×* I_k V_k` with
//! `a_k = A_k + J_k (q̇¹ − q̇⁰)/h` (A and V at the velocity the step's `f_r` used). The joint
//! at the top of a subtree supplies the difference:
//!
//! `W_j = Σ_{k ∈ subtree(j)} (I_k a_k + V_k ×* I_k V_k − w_k − m_k g + C_k V¹_k − e_k)`,
//!
//! a world wrench at the world origin, exerted by the parent on the subtree. Its projection
//! on joint j's axes is that joint's torque in the step, `τ_ext − K(q − q_rest) − (D + hK) q̇¹`
//! plus the joint-space constraint impulses (limits, head) over h; the rest is the
//! constraint force of the joint (what holds the bodies together).

use crate::data::Data;
use crate::model::Model;
use crate::spatial::Spatial;

/// Writes into `out` (one entry per joint) the world wrench at the world origin that each
/// joint's parent side exerts on its subtree during the step from `qdot_before` to
/// `qdot_after` of size `h` (see the module docs). `external` holds the constraint wrenches
/// on each body that `Data`'s applied wrenches do not (contact forces, dyn and dyn·cm, at the
/// world origin). Uses the kinematics in `data` (frames, inertias, and the twists and
/// velocity products the step's generalized force was formed at) and its applied wrenches
/// and dampers; scratch in `data` is overwritten.
pub fn joint_wrenches(
    model: &Model,
    data: &mut Data,
    qdot_before: &[f64],
    qdot_after: &[f64],
    h: f64,
    external: &[Spatial],
    out: &mut [Spatial],
) {
    let gravity = model.gravity();
    for (i, joint) in model.joints().iter().enumerate() {
        // J_k (q̇¹ − q̇⁰)/h and J_k q̇¹, accumulated down the tree.
        let (mut change, mut next) = match joint.parent {
            Some(p) => (data.accelerations[p], data.wrenches[p]),
            None => (Spatial::ZERO, Spatial::ZERO),
        };
        for a in joint.dofs() {
            let axis = &data.axes[a];
            change = change.add_scaled(axis, (qdot_after[a] - qdot_before[a]) / h);
            next = next.add_scaled(axis, qdot_after[a]);
        }
        data.accelerations[i] = change;
        data.wrenches[i] = next;
    }
    for i in 0..model.body_count() {
        let inertia = &data.inertias[i];
        let twist = &data.velocities[i];
        let accel = data.accelerations[i] + data.bias_accelerations[i];
        let weight =
            Spatial::point_force(data.body_frames[i].translation, gravity * model.bodies()[i].mass);
        out[i] = inertia.apply(&accel) + twist.cross_force(&inertia.apply(twist))
            - data.applied_wrenches[i]
            - weight
            + data.applied_damping[i].apply(&data.wrenches[i])
            - external[i];
    }
    for i in (0..model.body_count()).rev() {
        if let Some(parent) = model.joints()[i].parent {
            let w = out[i];
            out[parent] += w;
        }
    }
}
