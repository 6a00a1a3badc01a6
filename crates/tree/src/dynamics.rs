//! Stage 2, dynamics terms in reduced coordinates.
//!
//! - Mass matrix by the composite-rigid-body algorithm: with `I^c_j` the world inertia of the
//!   subtree of joint `j`, `M_ab = s_aᵀ I^c_j s_b` for every DOF `b` of joint `j` and every DOF
//!   `a` on the path from `j` to the root. This equals `Jᵀ M_m J` (tested) at a fraction of
//!   the cost, and is symmetric by construction.
//! - Inverse dynamics by recursive Newton–Euler in world coordinates: body accelerations
//!   `A_i + Σ s_a q̈_a`, body wrenches `w_i = I_i a_i + V_i ×* (I_i V_i) − w_applied,i`
//!   (gravity included), accumulated leaf to root, projected on the axes:
//!   `τ_a = s_aᵀ Σ_{subtree} w`. So `τ = M q̈ + C(q, q̇) − Sᵀ w_applied`.
//!
//! Run [`crate::forward_kinematics`] first.

use crate::data::Data;
use crate::model::Model;
use crate::spatial::Spatial;

/// Fills `data.mass_matrix` with `M(q)` (g·cm²/rad² for rotational DOFs).
pub fn mass_matrix(model: &Model, data: &mut Data) {
    accumulate_subtrees(model, &data.inertias, &mut data.composite);
    let n = model.dof_count();
    let m = &mut data.mass_matrix;
    m.fill(0.0);
    // Column b holds s_aᵀ I^c_j s_b for the DOFs a on b's path: rows a ≤ b, since parents'
    // DOFs come first. Fill those contiguous column entries, then mirror.
    for (j, joint) in model.joints().iter().enumerate() {
        for b in joint.dofs() {
            let momentum = data.composite[j].apply(&data.axes[b]);
            let column = m.col_mut(b).try_as_col_major_mut().map(|c| c.as_slice_mut());
            let Some(column) = column else { continue };
            for ancestor in model.path_to_root(j) {
                for a in ancestor.dofs() {
                    column[a] = data.axes[a].dot(&momentum);
                }
            }
        }
    }
    for b in 0..n {
        for a in 0..b {
            let value = m[(a, b)];
            m[(b, a)] = value;
        }
    }
}

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
    for i in (0..model.body_count()).rev() {
        let joint = &model.joints()[i];
        if let Some(parent) = joint.parent {
            let w = data.wrenches[i];
            data.wrenches[parent] += w;
        }
        for a in joint.dofs() {
            tau[a] = data.axes[a].dot(&data.wrenches[i]);
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

fn accumulate_subtrees(
    model: &Model,
    inertias: &[crate::spatial::RigidInertia],
    composite: &mut [crate::spatial::RigidInertia],
) {
    composite.copy_from_slice(inertias);
    for i in (0..model.body_count()).rev() {
        if let Some(parent) = model.joints()[i].parent {
            let c = composite[i];
            composite[parent] += c;
        }
    }
}
