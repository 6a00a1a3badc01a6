//! The mass matrix by the composite-rigid-body algorithm (CRBA), and the effective mass of
//! the implicit step, which is the same algorithm on augmented inertias.
//!
//! With `I^c_j` the world inertia of the subtree of joint `j`,
//! `M_ab = s_aᵀ I^c_j s_b` for every DOF `b` of joint `j` and every DOF `a` on the path from
//! `j` to the root. This equals `Jᵀ M_m J` (tested) at a fraction of the cost and is symmetric
//! by construction.
//!
//! The effective mass `M̃ = M + h Jᵀ C_m J + hD + h²K` adds the implicit point dampers of
//! [`Data::apply_point_damping`]: a damper `c` at the point `x` contributes `c P(x)ᵀP(x)`,
//! which is exactly the contribution of a point mass `c` at `x`. The CRBA being linear in the
//! body inertias, `M + h Jᵀ C_m J` is one CRBA pass on `I_k + h C_k`.
//!
//! Run [`crate::forward_kinematics`] first.

use faer::Mat;

use crate::data::{Data, ensure_square};
use crate::model::Model;
use crate::spatial::{RigidInertia, Spatial, SpatialComponents};

/// Fills `data.mass_matrix` with `M(q)` (g·cm²/rad² for rotational DOFs).
pub fn mass_matrix(model: &Model, data: &mut Data) {
    ensure_square(&mut data.mass_matrix, model.dof_count());
    composite_rigid_body(
        model,
        &data.axes,
        &data.axis_components,
        &data.inertias,
        &mut data.composite,
        &mut data.mass_matrix,
    );
}

/// Fills `data.effective_mass` with `M̃ = M + h Jᵀ C_m J + hD + h²K` for the step `h` (s), where
/// `C_m` are the point dampers applied this step and `D`, `K` include this step's joint servos
/// ([`Data::servo_stiffness`]) (treated implicitly, so a stiff drag or a
/// stiff tail controller on a light body cannot make the step unstable).
pub fn effective_mass(model: &Model, data: &mut Data, h: f64) {
    ensure_square(&mut data.effective_mass, model.dof_count());
    for ((augmented, inertia), damping) in
        data.augmented.iter_mut().zip(&data.inertias).zip(&data.applied_damping)
    {
        *augmented = *inertia;
        augmented.add_scaled(damping, h);
    }
    composite_rigid_body(
        model,
        &data.axes,
        &data.axis_components,
        &data.augmented,
        &mut data.composite,
        &mut data.effective_mass,
    );
    for (a, dof) in model.dofs().iter().enumerate() {
        let diagonal = data.joint_diagonal(dof, a, h);
        data.effective_mass[(a, a)] += diagonal;
    }
}

fn composite_rigid_body(
    model: &Model,
    axes: &[Spatial],
    axis_components: &SpatialComponents,
    inertias: &[RigidInertia],
    composite: &mut [RigidInertia],
    m: &mut Mat<f64>,
) {
    composite.copy_from_slice(inertias);
    for i in (0..model.body_count()).rev() {
        if let Some(parent) = model.joints()[i].parent {
            let c = composite[i];
            composite[parent] += c;
        }
    }
    m.fill(0.0);
    // Column b holds s_aᵀ I^c_j s_b for the DOFs a on b's path: rows a ≤ b, since parents'
    // DOFs come first. Fill those column entries, run by run, then mirror.
    for (j, joint) in model.joints().iter().enumerate() {
        for run in model.path_dof_runs(j) {
            for b in joint.dofs() {
                let momentum = composite[j].apply(&axes[b]);
                let products = axis_components.dots(run.clone(), &momentum);
                for (entry, product) in m.col_as_slice_mut(b)[run.clone()].iter_mut().zip(products)
                {
                    *entry = product;
                }
            }
        }
    }
    for b in 0..m.ncols() {
        for a in 0..b {
            let value = m[(a, b)];
            m[(b, a)] = value;
        }
    }
}
