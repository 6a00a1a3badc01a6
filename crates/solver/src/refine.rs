//! Iterative refinement of the answer on a fixed active set.
//!
//! With the free rows F fixed (their constraints hold as equalities, the other multipliers
//! stay on their bounds) the exact answer solves the reduced KKT system
//!
//! M̃q̇ − C_Fᵀλ_F = f̃ + C_Aᵀλ_A,  C_F q̇ + E_F λ_F = b_F  (E the compliances).
//!
//! Given the residuals r₁ = f̃ + Cᵀλ − M̃q̇ and r₂ = b_F − C_F q̇ − E_F λ_F of the current
//! (q̇, λ), the
//! correction solves the same system with right-hand side (r₁, r₂), by the Schur complement
//! on the factors already at hand (u = L⁻¹r₁):
//!
//! W_FF δλ_F = r₂ − Y_Fᵀu,  δq = L⁻ᵀ(u + Y_F δλ_F)  (W_FF holds E_F on its diagonal).
//!
//! The residuals are formed with the original M̃ and C, so each step removes the rounding of
//! the Y/W route (which loses accuracy when M̃ or W_FF is ill-conditioned). Steps stop when
//! the largest relative residual is at rounding level or no longer halves. With F empty this
//! is classic refinement of M̃q̇ = f̃.

use crate::contact_space::ContactSpace;
use crate::error::SolverError;
use crate::free_set::FreeSet;
use crate::linalg::{axpy, column_mut, try_capacity, zeroed};
use crate::mass_operator::FactoredMass;
use crate::problem::Problem;
use crate::residuals::{Stationarity, row_residual};

/// Relative residual below which refinement stops (a few units of rounding).
const ROUNDING_LEVEL: f64 = 1e-15;

/// The factored system of one solve, as refinement sees it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FactoredSystem<'a> {
    pub(crate) problem: &'a Problem<'a>,
    pub(crate) mass: &'a dyn FactoredMass,
    pub(crate) dual: &'a ContactSpace,
    pub(crate) free: &'a FreeSet,
}

/// What a refinement did: the corrections taken, and the stationarity of the answer it
/// returns when its last act was to measure it (`None` when it stopped at `max_steps`
/// after a correction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Refined {
    pub(crate) steps: usize,
    pub(crate) stationarity: Option<Stationarity>,
}

/// Scratch of the refinement (n, n and m entries; grow-only).
#[derive(Debug, Default)]
pub(crate) struct Refinement {
    residual: Vec<f64>,
    work: Vec<f64>,
    compact: Vec<f64>,
}

impl Refinement {
    /// Reserves room for problems of up to `dofs` velocities and `rows` rows.
    pub(crate) fn try_reserve(&mut self, dofs: usize, rows: usize) -> Result<(), SolverError> {
        try_capacity(&mut self.residual, dofs, "the refinement's residual")?;
        try_capacity(&mut self.work, dofs, "the refinement's scratch")?;
        try_capacity(&mut self.compact, rows, "the refinement's free rows")
    }

    /// Refines (q̇, λ) in place for at most `max_steps` corrections.
    pub(crate) fn run(
        &mut self,
        system: FactoredSystem<'_>,
        lambda: &mut [f64],
        qdot: &mut [f64],
        max_steps: usize,
    ) -> Refined {
        let FactoredSystem { problem, mass, dual, free } = system;
        zeroed(&mut self.residual, problem.dofs());
        zeroed(&mut self.work, problem.dofs());
        zeroed(&mut self.compact, free.indices().len());
        let mut previous = f64::INFINITY;
        for step in 0..max_steps {
            // r₁ = f̃ + Cᵀλ − M̃q̇ and r₂ = b_F − C_F q̇ − E_F λ_F, with their relative size.
            let (residual, work) = (&mut self.residual, &mut self.work);
            let supports = Some(dual.supports());
            let measured = Stationarity::measure(problem, qdot, lambda, supports, residual, work);
            let mut relative = measured.norm / measured.scale;
            for (r2, &i) in self.compact.iter_mut().zip(free.indices()) {
                let (v, s) = row_residual(problem, i, qdot, lambda, dual.supports()[i]);
                *r2 = -v;
                relative = relative.max(v.abs() / s);
            }
            if relative <= ROUNDING_LEVEL || relative > 0.5 * previous {
                return Refined { steps: step, stationarity: Some(measured) };
            }
            previous = relative;
            // u = L⁻¹r₁;  W_FF δλ = r₂ − Y_Fᵀu;  δq = L⁻ᵀ(u + Y_F δλ).
            mass.solve_lower(column_mut(&mut self.residual));
            for (r2, &i) in self.compact.iter_mut().zip(free.indices()) {
                *r2 -= dual.y_dot(i, &self.residual);
            }
            free.solve(&mut self.compact);
            for (&delta, &i) in self.compact.iter().zip(free.indices()) {
                lambda[i] += delta;
                dual.y_axpy(i, delta, &mut self.residual);
            }
            mass.solve_upper(column_mut(&mut self.residual));
            axpy(1.0, &self.residual, qdot);
        }
        Refined { steps: max_steps, stationarity: None }
    }
}
