//! The contact-space (dual) operator of the velocity problem.
//!
//! With M̃ = L Lᵀ, Y = L⁻¹Cᵀ (n × m) and z = L⁻¹f̃:
//!
//! - W = C M̃⁻¹ Cᵀ = YᵀY (m × m, positive semidefinite; singular when rows are duplicated),
//! - q_free = M̃⁻¹f̃ = L⁻ᵀz, and r = b − C q_free = b − Yᵀz,
//! - for any λ, q̇(λ) = M̃⁻¹(f̃ + Cᵀλ) = L⁻ᵀ(z + Yλ), and the row residuals are
//!   Cq̇(λ) − b = Wλ − r.
//!
//! Substituting q̇(λ) into the Lagrangian gives the dual QP
//! min ½λᵀWλ − λᵀr over the box (λ free on equalities, λ ≥ 0 on inequalities,
//! 0 ≤ λ ≤ weight on soft rows), whose gradient Wλ − r is exactly the vector of row
//! residuals: stationarity of the primal holds by construction, and the box QP's optimality
//! conditions are primal feasibility and complementarity.
//!
//! W is not regularised: duplicated or degenerate rows make it singular, and the active-set
//! method (`active_set.rs`) keeps the rows it factors linearly independent instead.

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par};

use crate::linalg::{column, column_mut};
use crate::mass_operator::FactoredMass;
use crate::problem::Problem;

/// Y, W, z, r and b of one solve (sizes n × m, m × m, n, m, m).
#[derive(Debug)]
pub(crate) struct ContactSpace {
    y: Mat<f64>,
    w: Mat<f64>,
    z: Vec<f64>,
    r: Vec<f64>,
    b: Vec<f64>,
}

impl ContactSpace {
    /// Empty buffers, sized by the first build.
    pub(crate) fn new() -> Self {
        Self {
            y: Mat::zeros(0, 0),
            w: Mat::zeros(0, 0),
            z: Vec::new(),
            r: Vec::new(),
            b: Vec::new(),
        }
    }

    /// Reserves room for problems of up to `dofs` velocities and `rows` rows.
    pub(crate) fn reserve(&mut self, dofs: usize, rows: usize) {
        self.y.reserve(dofs, rows);
        self.w.reserve(rows, rows);
        self.z.reserve(dofs);
        self.r.reserve(rows);
        self.b.reserve(rows);
    }

    /// Forms Y = L⁻¹Cᵀ, W = YᵀY, z = L⁻¹f̃ and r = b − Yᵀz for `problem`, with `factor`
    /// holding a factor of its M̃ (M̃ = L Lᵀ).
    pub(crate) fn build(&mut self, factor: &dyn FactoredMass, problem: &Problem<'_>) {
        let rows = problem.rows();
        let (n, m) = (problem.dofs(), rows.len());
        self.y.resize_with(n, m, |_, _| 0.0);
        self.y.copy_from(rows.transposed());
        factor.solve_lower(self.y.as_mut());
        self.w.resize_with(m, m, |_, _| 0.0);
        matmul(self.w.as_mut(), Accum::Replace, self.y.transpose(), self.y.as_ref(), 1.0, Par::Seq);

        self.update_force(factor, problem);
    }

    /// Recomputes z = L⁻¹f̃ and r = b − Yᵀz for a new f̃ and new right-hand sides b, keeping Y
    /// and W: for a problem whose M̃ and row coefficients are those of the last
    /// [`build`](Self::build).
    pub(crate) fn update_force(&mut self, factor: &dyn FactoredMass, problem: &Problem<'_>) {
        self.b.clear();
        self.b.extend_from_slice(problem.rows().rhs());
        self.z.clear();
        self.z.extend_from_slice(problem.force());
        factor.solve_lower(column_mut(&mut self.z));
        self.r.clear();
        self.r.extend_from_slice(&self.b);
        matmul(
            column_mut(&mut self.r),
            Accum::Add,
            self.y.transpose(),
            column(&self.z),
            -1.0,
            Par::Seq,
        );
    }

    /// Number of rows m of the last build.
    pub(crate) fn rows(&self) -> usize {
        self.b.len()
    }

    /// Number of DOFs n.
    pub(crate) fn dofs(&self) -> usize {
        self.z.len()
    }

    /// Column i of Y = L⁻¹Cᵀ, i.e. L⁻¹cᵢ (n).
    pub(crate) fn y_column(&self, i: usize) -> &[f64] {
        self.y.col_as_slice(i)
    }

    /// W = YᵀY (m × m).
    pub(crate) fn w(&self) -> MatRef<'_, f64> {
        self.w.as_ref()
    }

    /// r = b − C M̃⁻¹f̃ (m).
    pub(crate) fn r(&self) -> &[f64] {
        &self.r
    }

    /// b, the rows' right-hand sides (m): exact data, unlike r, whose Yᵀz term carries the
    /// rounding of large cancelling products when M̃ is ill-conditioned.
    pub(crate) fn b(&self) -> &[f64] {
        &self.b
    }

    /// out ← z + Yλ = Lᵀq̇(λ), whose norm is ‖q̇(λ)‖_M.
    pub(crate) fn lift(&self, lambda: &[f64], out: &mut [f64]) {
        out.copy_from_slice(&self.z);
        matmul(column_mut(out), Accum::Add, self.y.as_ref(), column(lambda), 1.0, Par::Seq);
    }

    /// q̇ ← M̃⁻¹(f̃ + Cᵀλ) = L⁻ᵀ(z + Yλ).
    pub(crate) fn recover(&self, factor: &dyn FactoredMass, lambda: &[f64], qdot: &mut [f64]) {
        self.lift(lambda, qdot);
        factor.solve_upper(column_mut(qdot));
    }
}
