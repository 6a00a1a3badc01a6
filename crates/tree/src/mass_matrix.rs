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

use std::ops::Range;

use faer::Mat;

use crate::data::Data;
use crate::model::Model;
use crate::spatial::{RigidInertia, Spatial};

/// Fills `data.mass_matrix` with `M(q)` (g·cm²/rad² for rotational DOFs).
pub fn mass_matrix(model: &Model, data: &mut Data) {
    composite_rigid_body(
        model,
        &data.axes,
        &data.inertias,
        &mut data.composite,
        &mut data.columns,
        &mut data.mass_matrix,
    );
}

/// Fills `data.effective_mass` with `M̃ = M + h Jᵀ C_m J + hD + h²K` for the step `h` (s), where
/// `C_m` are the point dampers applied this step (treated implicitly, so a stiff drag or a
/// stiff tail controller on a light body cannot make the step unstable).
pub fn effective_mass(model: &Model, data: &mut Data, h: f64) {
    for ((augmented, inertia), damping) in
        data.augmented.iter_mut().zip(&data.inertias).zip(&data.applied_damping)
    {
        *augmented = *inertia;
        augmented.add_scaled(damping, h);
    }
    composite_rigid_body(
        model,
        &data.axes,
        &data.augmented,
        &mut data.composite,
        &mut data.columns,
        &mut data.effective_mass,
    );
    for (a, dof) in model.dofs().iter().enumerate() {
        data.effective_mass[(a, a)] += h * dof.damping + h * h * dof.stiffness;
    }
}

/// Scratch of the CRBA's column loop, sized once per model.
#[derive(Debug, Clone, Default)]
pub(crate) struct ColumnScratch {
    /// The axes `s_a`, one array per coordinate (ω_x, ω_y, ω_z, v_x, v_y, v_z): the inner
    /// loop `M_ab = s_a · (I^c_j s_b)` over a then reads contiguous memory.
    axes: [Vec<f64>; 6],
    /// The DOFs on the path from a joint to the root, as contiguous ranges (one for a chain).
    runs: Vec<Range<usize>>,
}

impl ColumnScratch {
    /// Room for `dofs` axes and paths of up to `bodies` joints, so that the CRBA does not
    /// allocate.
    pub(crate) fn new(dofs: usize, bodies: usize) -> Self {
        Self {
            axes: std::array::from_fn(|_| Vec::with_capacity(dofs)),
            runs: Vec::with_capacity(bodies),
        }
    }

    /// Copies `axes` into the coordinate arrays.
    fn load_axes(&mut self, axes: &[Spatial]) {
        for (c, coordinate) in self.axes.iter_mut().enumerate() {
            coordinate.clear();
            coordinate.extend(axes.iter().map(|s| match c {
                0..3 => s.angular[c],
                _ => s.linear[c - 3],
            }));
        }
    }

    /// Fills `runs` with the DOFs on the path from joint `j` to the root, merging each joint's
    /// DOFs into the run of its child when they are adjacent.
    fn load_path(&mut self, model: &Model, j: usize) {
        self.runs.clear();
        for joint in model.path_to_root(j) {
            let dofs = joint.dofs();
            match self.runs.last_mut() {
                Some(run) if run.start == dofs.end => run.start = dofs.start,
                _ => self.runs.push(dofs),
            }
        }
    }

    /// `column[a] = s_a · p` for every `a` in `run`, with the operations in the order of
    /// [`Spatial::dot`] (so the same values), over contiguous arrays.
    fn write_products(&self, p: &Spatial, run: Range<usize>, column: &mut [f64]) {
        let [wx, wy, wz, vx, vy, vz] = self.axes.each_ref().map(|c| &c[run.clone()]);
        let column = &mut column[run];
        for (a, out) in column.iter_mut().enumerate() {
            let angular = wx[a] * p.angular.x + wy[a] * p.angular.y + wz[a] * p.angular.z;
            let linear = vx[a] * p.linear.x + vy[a] * p.linear.y + vz[a] * p.linear.z;
            *out = angular + linear;
        }
    }
}

fn composite_rigid_body(
    model: &Model,
    axes: &[Spatial],
    inertias: &[RigidInertia],
    composite: &mut [RigidInertia],
    scratch: &mut ColumnScratch,
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
    scratch.load_axes(axes);
    // Column b holds s_aᵀ I^c_j s_b for the DOFs a on b's path: rows a ≤ b, since parents'
    // DOFs come first. Fill those column entries, then mirror.
    for (j, joint) in model.joints().iter().enumerate() {
        scratch.load_path(model, j);
        for b in joint.dofs() {
            let momentum = composite[j].apply(&axes[b]);
            let column = m.col_as_slice_mut(b);
            for run in &scratch.runs {
                scratch.write_products(&momentum, run.clone(), column);
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
