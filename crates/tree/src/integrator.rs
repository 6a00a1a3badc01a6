//! Stage 3, the linearly implicit Euler step (REDMAX; `docs/physics.md` D3, "Time stepping").
//!
//! Damping and the spring's linearisation go to the left-hand side:
//! `M̃ = M + h Jᵀ C_m J + hD + h²K` (with the implicit point dampers `C_m`),
//! `f̃ = M q̇⁰ + h f_r(q⁰, q̇⁰)`, then `M̃ q̇¹ = f̃` (plus constraint
//! impulses, solved elsewhere) and `q¹ = q⁰ + h q̇¹`. With no constraints the solve is one
//! dense Cholesky factorisation of `M̃` (SPD: `M` is SPD and `D, K ≥ 0`).

use faer::linalg::cholesky::llt;
use faer::{Par, Spec};

use crate::data::{Data, ensure_square};
use crate::dynamics::{generalized_force, generalized_momentum};
use crate::error::TreeError;
use crate::kinematics::forward_kinematics;
use crate::mass_matrix::effective_mass;
use crate::model::Model;
use crate::state::State;

/// Fills `data.effective_momentum` with `f̃ = p + h f_r` from `data.momentum` (`p = M q̇⁰`) and
/// `data.generalized_force`, for the step size `h` (s).
pub fn assemble_effective_momentum(data: &mut Data, h: f64) {
    for ((f, p), force) in
        data.effective_momentum.iter_mut().zip(&data.momentum).zip(&data.generalized_force)
    {
        *f = p + h * force;
    }
}

/// Factors `M̃ = L Lᵀ` into `data.factor` (lower triangle). Fails if `M̃` is not numerically
/// positive definite.
pub fn factor_effective_mass(data: &mut Data, time: f64) -> Result<(), TreeError> {
    let n = data.effective_mass.nrows();
    ensure_square(&mut data.factor, n);
    data.factor.copy_from(&data.effective_mass);
    let stack = faer::dyn_stack::MemStack::new(&mut data.stack);
    llt::factor::cholesky_in_place(
        data.factor.as_mut(),
        Default::default(),
        Par::Seq,
        stack,
        Spec::default(),
    )
    .map(|_| ())
    .map_err(|e| match e {
        llt::factor::LltError::NonPositivePivot { index } => {
            TreeError::NotPositiveDefinite { time, pivot: index }
        }
    })
}

/// Solves `M̃ q̇¹ = f̃` with the factor from [`factor_effective_mass`] into `data.qdot_next`.
pub fn solve_unconstrained(data: &mut Data) {
    for (a, value) in data.effective_momentum.iter().enumerate() {
        data.qdot_next[(a, 0)] = *value;
    }
    let stack = faer::dyn_stack::MemStack::new(&mut data.stack);
    llt::solve::solve_in_place(data.factor.as_ref(), data.qdot_next.as_mut(), Par::Seq, stack);
}

/// Accepts new velocities and advances time and positions: `q̇ ← q̇¹`, `q ← q + h q̇¹`,
/// `t ← t + h`. Fails, leaving `state` unchanged, if any new velocity is not finite.
pub fn integrate(state: &mut State, qdot_next: &[f64], h: f64) -> Result<(), TreeError> {
    if let Some(dof) = qdot_next.iter().position(|v| !v.is_finite()) {
        return Err(TreeError::NonFinite { time: state.t, what: "qdot", dof });
    }
    for ((q, qdot), next) in state.q.iter_mut().zip(state.qdot.iter_mut()).zip(qdot_next) {
        *qdot = *next;
        *q += h * next;
    }
    state.t += h;
    Ok(())
}

/// One unconstrained step of size `h` (s): kinematics, dynamics, assemble, factor, solve,
/// integrate. Uses the applied forces in `data`. The state is checked first and is left unchanged on error.
pub fn step_unconstrained(
    model: &Model,
    state: &mut State,
    h: f64,
    data: &mut Data,
) -> Result<(), TreeError> {
    state.validate(model)?;
    forward_kinematics(model, &state.q, &state.qdot, data);
    effective_mass(model, data, h);
    generalized_momentum(model, data);
    generalized_force(model, &state.q, data);
    assemble_effective_momentum(data, h);
    factor_effective_mass(data, state.t)?;
    solve_unconstrained(data);
    let n = model.dof_count();
    let next = data.qdot_next.col(0);
    // `qdot_next` is a contiguous column: copy through a slice view without allocating.
    let next = next.try_as_col_major().map(|c| c.as_slice()).unwrap_or(&[]);
    if next.len() != n {
        return Err(TreeError::DimensionMismatch {
            what: "qdot_next",
            got: next.len(),
            expected: n,
        });
    }
    integrate(state, next, h)
}
