//! Stage 2, forces in reduced coordinates (the mass matrix is in the `mass_matrix` module).
//!
//! - Inverse dynamics by recursive Newton–Euler in world coordinates: body accelerations
//!   `A_i + Σ s_a q̈_a`, body wrenches `w_i = I_i a_i + V_i ×* (I_i V_i) − w_applied,i`
//!   (gravity included), accumulated leaf to root, projected on the axes:
//!   `τ_a = s_aᵀ Σ_{subtree} w`. So `τ = M q̈ + C(q, q̇) − Sᵀ w_applied`.
//!
//! Run [`crate::forward_kinematics`] first.

use crate::data::Data;
use crate::model::Model;
use crate::spatial::Spatial;

/// Inverse dynamics: writes `τ = M q̈ + C(q, q̇) − Sᵀ w_applied − τ_gravity` into `tau` (one
/// entry per DOF). With `qddot = None` it uses `q̈ = 0` and gives the negated smooth force.
/// Applied joint torques are not included.
pub fn inverse_dynamics(model: &Model, data: &mut Data, qddot: Option<&[f64]>, tau: &mut [f64]) {
    let gravity = model.gravity();
    for (i, joint) in model.joints().iter().enumerate() {
        let mut accel = data.bias_accelerations[i];
        if let Some(parent) = joint.parent {
            // The bias accelerations already sum along the path; q̈ terms must be added
            // along it too.
            accel += data.accelerations[parent] - data.bias_accelerations[parent];
        }
        if let Some(qdd) = qddot {
            for a in joint.dofs() {
                accel = accel.add_scaled(&data.axes[a], qdd[a]);
            }
        }
        data.accelerations[i] = accel;
        let inertia = &data.inertias[i];
        let twist = &data.velocities[i];
        let weight =
            Spatial::point_force(data.body_frames[i].translation, gravity * model.bodies()[i].mass);
        data.wrenches[i] = inertia.apply(&accel) + twist.cross_force(&inertia.apply(twist))
            - data.applied_wrenches[i]
            - weight;
    }
    project_subtree_sums(model, &data.axes, &mut data.wrenches, tau);
}

/// Fills `data.momentum` with the generalized momentum `p = M q̇` at the velocities of the
/// last [`crate::forward_kinematics`] call, in O(bodies): `p_a = s_aᵀ Σ_{k ∈ subtree(a)} I_k V_k`.
pub fn generalized_momentum(model: &Model, data: &mut Data) {
    for i in 0..model.body_count() {
        data.wrenches[i] = data.inertias[i].apply(&data.velocities[i]);
    }
    project_subtree_sums(model, &data.axes, &mut data.wrenches, &mut data.momentum);
}

/// The backward pass shared by RNEA and the momentum: sums the per-body vectors over each
/// subtree, leaf to root (in place), and projects each joint's sum on its axes:
/// `out_a = s_aᵀ Σ_{k ∈ subtree(a)} w_k`.
fn project_subtree_sums(model: &Model, axes: &[Spatial], sums: &mut [Spatial], out: &mut [f64]) {
    for i in (0..model.body_count()).rev() {
        let joint = &model.joints()[i];
        if let Some(parent) = joint.parent {
            let w = sums[i];
            sums[parent] += w;
        }
        for a in joint.dofs() {
            out[a] = axes[a].dot(&sums[i]);
        }
    }
}

/// Fills `data.generalized_force` with
/// `f_r = −C(q, q̇) + Sᵀ w_applied + τ_gravity + τ_ext − K(q − q_rest)`:
/// the right-hand side of `M q̈ = f_r − D q̇`, without the damping that the integrator treats
/// implicitly.
pub fn generalized_force(model: &Model, q: &[f64], data: &mut Data) {
    let mut f = std::mem::take(&mut data.generalized_force);
    inverse_dynamics(model, data, None, &mut f);
    for (a, dof) in model.dofs().iter().enumerate() {
        f[a] = -f[a] + data.applied_torques[a] - dof.stiffness * (q[a] - dof.rest);
    }
    data.generalized_force = f;
}

/// The kinetic energy `½ Σᵢ Vᵢ·(Iᵢ Vᵢ)` (erg = g·cm²/s²) at the twists and inertias of the last
/// [`crate::forward_kinematics`] call.
pub fn kinetic_energy(data: &Data) -> f64 {
    0.5 * data.velocities.iter().zip(&data.inertias).map(|(v, i)| v.dot(&i.apply(v))).sum::<f64>()
}
