//! Everything derived from the state, plus scratch, allocated once per model.
//!
//! Each field says which stage fills it. Stages are free functions in [`crate::kinematics`],
//! [`crate::dynamics`] and [`crate::integrator`]; a field is valid only after its stage ran
//! for the current state.

use faer::Mat;
use faer::dyn_stack::{MemBuffer, StackReq};
use glam::DVec3;

use crate::model::Model;
use crate::spatial::{RigidInertia, Spatial, SpatialComponents, Transform};

/// Derived quantities and scratch for one model. Create with [`Data::new`]; reuse across steps
/// so that stepping does not allocate.
pub struct Data {
    /// World frame of each joint after its rotations, `E_wj` (kinematics).
    pub joint_frames: Vec<Transform>,
    /// World frame of each body (centre of mass, principal axes), `E_wb` (kinematics).
    pub body_frames: Vec<Transform>,
    /// World twist at the origin of each DOF's unit motion, `s_a` (kinematics). Column `a` of
    /// the world Jacobian.
    pub axes: Vec<Spatial>,
    /// The same axes stored by component (kinematics), for loops over many DOFs.
    pub axis_components: SpatialComponents,
    /// Time derivative of each axis, `ṡ_a = V_frame ×ₘ s_a` (kinematics).
    pub axis_rates: Vec<Spatial>,
    /// World twist at the origin of each body, `V_i = Σ_{a ∈ anc(i)} s_a q̇_a` (kinematics).
    pub velocities: Vec<Spatial>,
    /// Velocity-product acceleration of each body, `A_i = Σ_{a ∈ anc(i)} ṡ_a q̇_a`: the body's
    /// world spatial acceleration when `q̈ = 0` (kinematics).
    pub bias_accelerations: Vec<Spatial>,
    /// World spatial inertia of each body at the origin (kinematics).
    pub inertias: Vec<RigidInertia>,
    /// Applied world wrenches at the origin, per body (input: cleared by
    /// [`Data::clear_applied`], filled by [`Data::apply_point_force`]).
    pub applied_wrenches: Vec<Spatial>,
    /// Applied joint torques `τ_ext` per DOF (input, dyn·cm).
    pub applied_torques: Vec<f64>,
    /// Implicit point dampers per body, in inertia form (input: cleared by
    /// [`Data::clear_applied`], filled by [`Data::apply_point_damping`]).
    pub applied_damping: Vec<RigidInertia>,
    /// Implicit joint servo stiffness per DOF (input, dyn·cm/rad; cleared by
    /// [`Data::clear_applied`]): a servo `τ = k(q* − q¹) − c(q̇¹ − q̇*)` at the step's new
    /// state puts `h c + h² k` into `M̃` (here and in [`Data::servo_damping`]) and its
    /// explicit part `k(q* − q⁰) + c q̇*` into [`Data::applied_torques`], so that no gain can
    /// destabilise the step (as the joints' own springs, `docs/physics.md` D3).
    pub servo_stiffness: Vec<f64>,
    /// Implicit joint servo damping per DOF (input, dyn·cm·s/rad; see
    /// [`Data::servo_stiffness`]).
    pub servo_damping: Vec<f64>,
    /// Reduced mass matrix `M = Jᵀ M_m J`, n×n (mass_matrix::mass_matrix; not needed by the
    /// step, which builds `M̃` directly). Like [`Data::effective_mass`] and [`Data::factor`],
    /// allocated by the first stage that fills it (0×0 before): a caller that never forms the
    /// dense matrices (the sparse backend, position-only kinematics) holds no n×n buffer.
    pub mass_matrix: Mat<f64>,
    /// Generalized force `f_r = −C(q, q̇) + Sᵀ w_applied + τ_ext − K(q − q_rest)`: everything
    /// but damping and constraints, per DOF (dynamics::generalized_force).
    pub generalized_force: Vec<f64>,
    /// Generalized momentum `p = M q̇` at the kinematics velocities (dynamics::generalized_momentum).
    pub momentum: Vec<f64>,
    /// Effective mass `M̃ = M + h Jᵀ C_m J + hD + h²K` (mass_matrix::effective_mass).
    pub effective_mass: Mat<f64>,
    /// Effective momentum `f̃ = M q̇⁰ + h f_r` (integrator::assemble_effective_momentum).
    pub effective_momentum: Vec<f64>,
    /// Lower Cholesky factor of `M̃` (integrator::factor_effective_mass).
    pub factor: Mat<f64>,
    /// The new velocities `q̇¹` of the last solve (integrator).
    pub qdot_next: Mat<f64>,
    pub(crate) composite: Vec<RigidInertia>,
    pub(crate) augmented: Vec<RigidInertia>,
    pub(crate) wrenches: Vec<Spatial>,
    pub(crate) accelerations: Vec<Spatial>,
    pub(crate) stack: MemBuffer,
}

/// Makes `matrix` n×n (zeros) unless it already is: the one allocation of a dense buffer, at
/// the first stage that fills it.
pub(crate) fn ensure_square(matrix: &mut Mat<f64>, n: usize) {
    if matrix.nrows() != n || matrix.ncols() != n {
        *matrix = Mat::zeros(n, n);
    }
}

impl Data {
    /// Allocates all buffers for `model`.
    pub fn new(model: &Model) -> Self {
        let nb = model.body_count();
        let n = model.dof_count();
        let req = StackReq::any_of(&[
            faer::linalg::cholesky::llt::factor::cholesky_in_place_scratch::<f64>(
                n,
                faer::Par::Seq,
                Default::default(),
            ),
            faer::linalg::cholesky::llt::solve::solve_in_place_scratch::<f64>(n, 1, faer::Par::Seq),
        ]);
        Self {
            joint_frames: vec![Transform::IDENTITY; nb],
            body_frames: vec![Transform::IDENTITY; nb],
            axes: vec![Spatial::ZERO; n],
            axis_components: SpatialComponents::with_capacity(n),
            axis_rates: vec![Spatial::ZERO; n],
            velocities: vec![Spatial::ZERO; nb],
            bias_accelerations: vec![Spatial::ZERO; nb],
            inertias: vec![RigidInertia::ZERO; nb],
            applied_wrenches: vec![Spatial::ZERO; nb],
            applied_torques: vec![0.0; n],
            applied_damping: vec![RigidInertia::ZERO; nb],
            servo_stiffness: vec![0.0; n],
            servo_damping: vec![0.0; n],
            mass_matrix: Mat::zeros(0, 0),
            generalized_force: vec![0.0; n],
            momentum: vec![0.0; n],
            effective_mass: Mat::zeros(0, 0),
            effective_momentum: vec![0.0; n],
            factor: Mat::zeros(0, 0),
            qdot_next: Mat::zeros(n, 1),
            composite: vec![RigidInertia::ZERO; nb],
            augmented: vec![RigidInertia::ZERO; nb],
            wrenches: vec![Spatial::ZERO; nb],
            accelerations: vec![Spatial::ZERO; nb],
            stack: MemBuffer::new(req),
        }
    }

    /// Removes all applied wrenches, joint torques, dampers and servos.
    pub fn clear_applied(&mut self) {
        self.applied_wrenches.fill(Spatial::ZERO);
        self.applied_torques.fill(0.0);
        self.applied_damping.fill(RigidInertia::ZERO);
        self.servo_stiffness.fill(0.0);
        self.servo_damping.fill(0.0);
    }

    /// The joint diagonal of `M̃` at DOF `a` for the step `h`: `h d + h² k` of the joint's own
    /// damper and spring plus `h c + h² k` of this step's servo ([`Data::servo_stiffness`]).
    pub fn joint_diagonal(&self, dof: &crate::DofParams, a: usize, h: f64) -> f64 {
        h * dof.damping
            + h * h * dof.stiffness
            + (h * self.servo_damping[a] + h * h * self.servo_stiffness[a])
    }

    /// Adds an implicit linear damper at the world point `x` (cm) of `body`: the force
    /// `−c ẋ` (dyn) with `c` in dyn·s/cm, evaluated at the new velocity of the step (it enters
    /// `M̃` as `h c PᵀP`, so no size of `c` can destabilise the step). Water drag and the
    /// derivative part of a PD controller use it. The caller checks `body`.
    pub fn apply_point_damping(&mut self, body: usize, x: DVec3, coefficient: f64) {
        self.applied_damping[body].add_scaled(&RigidInertia::point(coefficient, x), 1.0);
    }

    /// Applies a world force `f` (dyn) at the world point `x` (cm) of `body` for the next
    /// dynamics evaluation: adds the wrench `(x × f; f)`. The caller checks `body` (see
    /// [`Model::check_body`]).
    pub fn apply_point_force(&mut self, body: usize, x: DVec3, f: DVec3) {
        self.applied_wrenches[body] += Spatial::point_force(x, f);
    }

    /// World position of the centre of `body` (kinematics).
    pub fn body_centre(&self, body: usize) -> DVec3 {
        self.body_frames[body].translation
    }
}

impl std::fmt::Debug for Data {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Data")
            .field("bodies", &self.body_frames.len())
            .field("dofs", &self.axes.len())
            .finish_non_exhaustive()
    }
}
