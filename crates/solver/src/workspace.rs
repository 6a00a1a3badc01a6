//! The solver workspace: path selection, the contact-space pipeline, and the answer.
//!
//! Path by the rows present (reported as [`SolvePath`]):
//!
//! 1. no rows: M̃q̇ = f̃ by Cholesky, q̇ = L⁻ᵀL⁻¹f̃;
//! 2. equalities only: KKT by the Schur complement, W μ = b − G M̃⁻¹f̃ with W = G M̃⁻¹Gᵀ,
//!    q̇ = M̃⁻¹(f̃ + Gᵀμ);
//! 3. any (soft) inequality: the QP, by the contact-space dual (default) or clarabel.
//!
//! Paths 1–3 (contact space) are one pipeline: factor M̃ = LLᵀ; form Y = L⁻¹Cᵀ, W = YᵀY,
//! r = b − C M̃⁻¹f̃ (`contact_space.rs`); minimise the dual over its box by the active-set
//! method (`active_set.rs`; with only equalities it is one Schur-complement solve, with no
//! rows it is empty); recover q̇ = M̃⁻¹(f̃ + Cᵀλ); refine on the final active set
//! (`refine.rs`); verify the bound rows against the refined q̇ and resume the active set if
//! one is violated (at most `VERIFICATION_PASSES` times). So the QP path equals the KKT path
//! when no inequality is active, and the KKT path with no rows is the unconstrained path, by
//! construction.
//!
//! Output: q̇ (n), λ (m, in row order) and per-tag generalized impulses C_gᵀλ_g (n each,
//! g·cm²/s per rotational DOF). **Impulses, not forces**: the generalized force of a tag
//! over the step is C_gᵀλ_g / h (dyn·cm per rotational DOF), which the caller forms with its h.
//!
//! M̃ comes as a dense matrix, factored here by Cholesky, or as an operator with its own
//! factor ([`crate::MassOperator`], the O(n) tree-structured factor of `hagfish-sparse`):
//! the pipeline only uses L⁻¹, L⁻ᵀ and M̃x, so both share every line of it.
//!
//! All buffers live here and only grow, so repeated solves of the same size do not allocate
//! (the clarabel backend excepted).

use std::sync::atomic::AtomicBool;

use faer::Mat;

use crate::active_set::{ActiveSet, ActiveSetLimits, Termination};
use crate::clarabel_reference;
use crate::contact_space::{ContactSpace, ReducedScratch};
use crate::error::SolverError;
use crate::linalg::{try_capacity, zeroed};
use crate::mass_factor::MassFactor;
use crate::mass_operator::{FactoredMass, Mass};
use crate::options::{QpBackend, SolverOptions, WarmStart};
use crate::problem::Problem;
use crate::refine::{FactoredSystem, Refined, Refinement};
use crate::report::{SolvePath, SolveReport, SolveStatus};
use crate::residuals::{
    Evaluation, Stationarity, evaluate, row_residuals, row_residuals_of_products,
};
use crate::rows::{PerTag, RowKind, RowTag, Rows};

/// How often a refined answer may send a violated bound row back to the active-set method.
const VERIFICATION_PASSES: usize = 4;

/// Owns every buffer of the velocity solve and the answer of the last one.
#[derive(Debug)]
pub struct SolverWorkspace {
    options: SolverOptions,
    mass: MassFactor,
    dual: ContactSpace,
    active: ActiveSet,
    refinement: Refinement,
    /// Eᵀλ when the velocity is recovered from λ.
    folded: ReducedScratch,
    velocity: Vec<f64>,
    multipliers: Vec<f64>,
    impulses: Mat<f64>,
    /// The columns of `impulses` that may hold non-zero values (tags that had rows in the
    /// last solve): only they and the tags with rows now are cleared, so a long chain with a
    /// few kinds of rows does not clear `RowTag::COUNT` columns of n per solve.
    impulses_written: PerTag<bool>,
    residual: Vec<f64>,
    work: Vec<f64>,
    /// (vᵢ, sᵢ) of every row at the answer (`residuals::row_residuals`).
    row_residuals: Vec<(f64, f64)>,
    report: SolveReport,
    /// True when `mass` and `dual` hold the factor and matrices of the last solve's M̃ and rows.
    contact_space_ready: bool,
}

/// What a solve may take over from the previous one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Reuse {
    /// Factor M̃ and build the contact-space matrices afresh.
    Nothing,
    /// M̃ and the rows are unchanged: keep the factor, Y and W.
    MassAndRows,
}

impl Default for SolverWorkspace {
    fn default() -> Self {
        Self::new(SolverOptions::default())
    }
}

impl SolverWorkspace {
    /// An empty workspace; buffers are sized by the first solve.
    pub fn new(options: SolverOptions) -> Self {
        Self {
            options,
            mass: MassFactor::new(),
            dual: ContactSpace::new(),
            active: ActiveSet::default(),
            refinement: Refinement::default(),
            folded: ReducedScratch::default(),
            velocity: Vec::new(),
            multipliers: Vec::new(),
            impulses: Mat::zeros(0, RowTag::COUNT),
            impulses_written: PerTag::default(),
            residual: Vec::new(),
            work: Vec::new(),
            row_residuals: Vec::new(),
            report: SolveReport::default(),
            contact_space_ready: false,
        }
    }

    /// Sizes every buffer for problems of up to `dofs` velocities and `rows` rows, so that
    /// contact-space solves within those sizes never allocate (larger ones still work and
    /// grow the buffers).
    ///
    /// # Errors
    /// [`SolverError::Allocation`] if a buffer cannot be allocated (the largest are the
    /// contact-space matrices, `dofs` × `rows` and `rows` × `rows`).
    pub fn try_reserve(&mut self, dofs: usize, rows: usize) -> Result<(), SolverError> {
        self.dual.try_reserve(dofs, rows)?;
        self.active.try_reserve(dofs, rows)?;
        self.refinement.try_reserve(dofs, rows)?;
        self.folded.try_reserve(rows)?;
        for buffer in [&mut self.velocity, &mut self.residual, &mut self.work] {
            try_capacity(buffer, dofs, "a solver vector over the DOFs")?;
        }
        try_capacity(&mut self.multipliers, rows, "the multipliers")?;
        try_capacity(&mut self.row_residuals, rows, "the row residuals")
    }

    /// The options in use.
    pub fn options(&self) -> &SolverOptions {
        &self.options
    }

    /// Replaces the options (takes effect at the next solve).
    pub fn set_options(&mut self, options: SolverOptions) {
        self.options = options;
    }

    /// Solves `problem`: minimise ½q̇ᵀM̃q̇ − q̇ᵀf̃ subject to its rows. The answer stays in the
    /// workspace (see [`velocity`](Self::velocity), [`multipliers`](Self::multipliers),
    /// [`tag_impulse`](Self::tag_impulse)); how it went is the returned report. Errors
    /// only when M̃ is not positive definite (everything else was validated by `Problem`).
    pub fn solve(&mut self, problem: &Problem<'_>) -> Result<&SolveReport, SolverError> {
        self.solve_with(problem, Reuse::Nothing)
    }

    /// Validates M̃ (`mass`) and the rows' coefficients once and returns a handle that solves
    /// them with any f̃ and right-hand sides b, keeping the factor of M̃ and the contact-space
    /// matrices Y = L⁻¹Cᵀ, W = YᵀY between its solves (see [`Factored`]).
    pub fn factor<'a>(
        &'a mut self,
        mass: Mass<'a>,
        rows: &'a Rows,
    ) -> Result<Factored<'a>, SolverError> {
        let problem = Problem::with_mass(mass, rows)?;
        Ok(Factored { workspace: self, problem, solved: false })
    }

    fn solve_with(
        &mut self,
        problem: &Problem<'_>,
        reuse: Reuse,
    ) -> Result<&SolveReport, SolverError> {
        let same_shape = self.contact_space_ready
            && problem.rows().len() == self.dual.rows()
            && problem.dofs() == self.dual.dofs();
        let reuse = if same_shape { reuse } else { Reuse::Nothing };
        let rows = problem.rows();
        let (n, m) = (problem.dofs(), rows.len());
        let path = match (m, rows.has_inequalities()) {
            (0, _) => SolvePath::Unconstrained,
            (_, false) => SolvePath::Kkt,
            (_, true) => SolvePath::Qp,
        };
        let backend = (path == SolvePath::Qp).then_some(self.options.backend);
        if backend == Some(QpBackend::ContactSpace) {
            let friction = rows.kinds().iter().position(|k| matches!(k, RowKind::Friction { .. }));
            if let Some(row) = friction {
                return Err(SolverError::FrictionConeNeedsClarabel { row });
            }
        }
        let warm_started = backend == Some(QpBackend::ContactSpace)
            && self.options.warm_start == WarmStart::PreviousMultipliers
            && !self.multipliers.is_empty();
        if warm_started {
            self.multipliers.resize(m, 0.0);
        } else {
            zeroed(&mut self.multipliers, m);
        }
        zeroed(&mut self.velocity, n);
        zeroed(&mut self.residual, n);
        zeroed(&mut self.work, n);

        let (status, iterations, refined) = match backend {
            Some(QpBackend::Clarabel) => {
                let outcome =
                    clarabel_reference::solve(problem, &mut self.velocity, &mut self.multipliers);
                let (qdot, lambda) = (&self.velocity, &self.multipliers);
                row_residuals(problem, qdot, lambda, None, &mut self.row_residuals);
                (outcome.status, outcome.iterations, Refined { steps: 0, stationarity: None })
            }
            _ => self.solve_contact_space(problem, reuse)?,
        };
        self.contact_space_ready = backend != Some(QpBackend::Clarabel);
        let stationarity = refined.stationarity.unwrap_or_else(|| {
            let (qdot, lambda) = (&self.velocity, &self.multipliers);
            Stationarity::measure(problem, qdot, lambda, None, &mut self.residual, &mut self.work)
        });
        let evaluation = evaluate(
            problem,
            &self.multipliers,
            stationarity,
            &self.row_residuals,
            self.options.acceptance,
        );
        self.report = SolveReport {
            path,
            backend,
            status: self.judge(status, &evaluation),
            iterations,
            refinement_steps: refined.steps,
            warm_started,
            rows_per_tag: rows.count_per_tag(),
            active_per_tag: evaluation.active_per_tag,
            residuals: evaluation.residuals,
            slack: evaluation.slack,
            gram_rows_saved: match backend {
                Some(QpBackend::Clarabel) => 0,
                _ => self.dual.gram_rows_saved(),
            },
        };
        problem.check_stop()?;
        self.collect_impulses(problem);
        Ok(&self.report)
    }

    /// q̇ of the last solve (n).
    pub fn velocity(&self) -> &[f64] {
        &self.velocity
    }

    /// λ of the last solve (m, in row order): impulses, ≥ 0 on inequalities.
    pub fn multipliers(&self) -> &[f64] {
        &self.multipliers
    }

    /// Replaces the multipliers the next warm-started solve starts from (one per row of its
    /// problem): the caller's start, e.g. the last step's multipliers matched to this step's
    /// rows (`hagfish_sim`'s warm start), which a resumed run restores exactly.
    pub fn set_multipliers(&mut self, lambda: &[f64]) {
        self.multipliers.clear();
        self.multipliers.extend_from_slice(lambda);
    }

    /// C_gᵀλ_g of the last solve (n): the generalized impulse of the rows tagged `tag`;
    /// divide by h for the generalized force (dyn·cm per rotational DOF).
    pub fn tag_impulse(&self, tag: RowTag) -> &[f64] {
        self.impulses.col_as_slice(tag.index())
    }

    /// Report of the last solve.
    pub fn report(&self) -> &SolveReport {
        &self.report
    }

    /// Factor, dual, active set, recovery, refinement and primal verification; returns the
    /// method's own status (`Solved`, `MaxIterations` or `Infeasible`), the active-set
    /// iterations and what the refinements did (all their steps, the last one's
    /// stationarity: it refined the answer returned). Leaves the row residuals of the answer
    /// in `row_residuals`.
    fn solve_contact_space(
        &mut self,
        problem: &Problem<'_>,
        reuse: Reuse,
    ) -> Result<(SolveStatus, usize, Refined), SolverError> {
        if reuse == Reuse::Nothing {
            self.contact_space_ready = false;
            if let Mass::Dense(mass) = problem.mass() {
                self.mass.factor(mass)?;
            }
        }
        let factor: &dyn FactoredMass = match problem.mass() {
            Mass::Dense(_) => &self.mass,
            Mass::Operator(operator) => operator,
        };
        match reuse {
            Reuse::Nothing => self.dual.build(factor, problem)?,
            Reuse::MassAndRows => self.dual.update_force(factor, problem),
        }
        let limits = ActiveSetLimits {
            max_iterations: self.options.max_iterations,
            release_tolerance: self.options.release_tolerance,
            stop: problem.stop(),
        };
        let mut outcome =
            self.active.solve(&self.dual, problem.rows().kinds(), &mut self.multipliers, limits);
        let mut iterations = outcome.iterations;
        let mut refined = Refined { steps: 0, stationarity: None };
        for pass in 0..=VERIFICATION_PASSES {
            problem.check_stop()?;
            self.dual.recover(factor, &self.multipliers, &mut self.folded, &mut self.velocity);
            let system = FactoredSystem {
                problem,
                mass: factor,
                dual: &self.dual,
                free: self.active.free(),
            };
            let run = self.refinement.run(
                system,
                &mut self.multipliers,
                &mut self.velocity,
                self.options.max_refinement_steps,
            );
            refined = Refined { steps: refined.steps + run.steps, ..run };
            let (qdot, lambda) = (&self.velocity, &self.multipliers);
            let residuals = &mut self.row_residuals;
            self.dual.row_products(problem.rows(), qdot, &mut self.folded, residuals);
            row_residuals_of_products(problem, lambda, residuals);
            if outcome.termination != Termination::Optimal || pass == VERIFICATION_PASSES {
                break;
            }
            let tolerance = self.options.release_tolerance;
            let Some(row) = self.active.violated_bound(&self.row_residuals, tolerance) else {
                break;
            };
            let left = ActiveSetLimits {
                max_iterations: limits.max_iterations.saturating_sub(iterations),
                ..limits
            };
            outcome = self.active.resume(&self.dual, &mut self.multipliers, left, row);
            iterations += outcome.iterations;
        }
        let contradiction =
            self.active.equalities_contradict(&self.row_residuals, self.options.acceptance);
        let status = match outcome.termination {
            Termination::Optimal if contradiction => SolveStatus::Infeasible,
            Termination::Optimal => SolveStatus::Solved,
            Termination::MaxIterations => SolveStatus::MaxIterations,
            Termination::Infeasible => SolveStatus::Infeasible,
            Termination::Stopped => return Err(SolverError::Stopped),
        };
        Ok((status, iterations, refined))
    }

    /// Final status: non-finite numbers are a numerical error; a "solved" answer whose
    /// residuals exceed the acceptance is inexact; other outcomes stand.
    fn judge(&self, status: SolveStatus, evaluation: &Evaluation) -> SolveStatus {
        let finite = self.velocity.iter().chain(&self.multipliers).all(|v| v.is_finite());
        match status {
            _ if !finite => SolveStatus::NumericalError,
            SolveStatus::Solved
                if evaluation.residuals.worst_relative > self.options.acceptance =>
            {
                SolveStatus::SolvedInexact
            }
            _ => status,
        }
    }

    /// impulse_g = Σ_{i tagged g} λᵢcᵢ for every tag g.
    fn collect_impulses(&mut self, problem: &Problem<'_>) {
        let rows = problem.rows();
        if self.impulses.nrows() != problem.dofs() {
            self.impulses.resize_with(problem.dofs(), RowTag::COUNT, |_, _| 0.0);
            self.impulses.fill(0.0);
            self.impulses_written = PerTag::default();
        }
        for (tag, &count) in rows.count_per_tag().iter() {
            if count > 0 || self.impulses_written[tag] {
                self.impulses.col_as_slice_mut(tag.index()).fill(0.0);
            }
            self.impulses_written[tag] = count > 0;
        }
        // Rows with λᵢ = 0 would add ±0 to each entry: skipped (most pyramid edges).
        let multipliers = self.multipliers.iter().zip(rows.sources()).enumerate();
        for (i, (&multiplier, source)) in multipliers.filter(|&(_, (&l, _))| l != 0.0) {
            let impulse = self.impulses.col_as_slice_mut(source.tag.index());
            rows.coefficients_of(i).add_scaled_to(multiplier, impulse);
        }
    }
}

/// One M̃ and one set of row coefficients, validated, solved with any f̃ and right-hand sides
/// b: the first [`solve`](Self::solve) factors M̃ and forms Y = L⁻¹Cᵀ and W = YᵀY, later ones
/// keep them and recompute only L⁻¹f̃ and the dual's linear term, starting the active set from
/// the last multipliers (a velocity-product refresh or tightened bounds within one step).
///
/// The handle borrows the workspace, M̃ and the rows for as long as it lives, so a factor
/// cannot be used with another M̃, other rows or changed coefficients: the compiler refuses.
///
/// ```compile_fail,E0502
/// # use faer::Mat;
/// # use hagfish_solver::{Mass, RowKind, RowSource, RowTag, Rows, SolverWorkspace};
/// let mass = Mat::<f64>::identity(1, 1);
/// let mut rows = Rows::new(1);
/// let mut workspace = SolverWorkspace::default();
/// let mut factored = workspace.factor(Mass::Dense(mass.as_ref()), &rows)?;
/// rows.push(RowKind::Inequality, RowSource::new(RowTag::new(0), 0), 0.0, &[1.0])?;
/// factored.solve(&[-1.0], &[0.0])?; // stale: the rows changed after the factor
/// # Ok::<(), hagfish_solver::SolverError>(())
/// ```
///
/// ```compile_fail,E0502
/// # use faer::Mat;
/// # use hagfish_solver::{Mass, Rows, SolverWorkspace};
/// let mut mass = Mat::<f64>::identity(1, 1);
/// let rows = Rows::new(1);
/// let mut workspace = SolverWorkspace::default();
/// let mut factored = workspace.factor(Mass::Dense(mass.as_ref()), &rows)?;
/// mass[(0, 0)] = 2.0;
/// factored.solve(&[-1.0], &[])?; // stale: M̃ changed after the factor
/// # Ok::<(), hagfish_solver::SolverError>(())
/// ```
#[derive(Debug)]
pub struct Factored<'a> {
    workspace: &'a mut SolverWorkspace,
    /// M̃ and the rows, validated; f̃ and b empty.
    problem: Problem<'a>,
    /// True after the first solve (which factors).
    solved: bool,
}

impl<'a> Factored<'a> {
    /// Ends every solve of this handle with [`SolverError::Stopped`] once `flag` is set (polled
    /// between the blocks of W = YᵀY and the active set's iterations): a stop asked for by a
    /// signal does not wait for a solve of a huge body.
    #[must_use]
    pub fn stop_when(mut self, flag: Option<&'a AtomicBool>) -> Self {
        self.problem = self.problem.stopping_when(flag);
        self
    }

    /// Solves with f̃ = `force` (length n) and b = `rhs` (one per row, in row order); errors
    /// on a size mismatch or a non-finite value, or when M̃ is not positive definite.
    pub fn solve(&mut self, force: &[f64], rhs: &[f64]) -> Result<&SolveReport, SolverError> {
        let problem = self.problem.with_force_and_rhs(force, rhs)?;
        let reuse = if self.solved { Reuse::MassAndRows } else { Reuse::Nothing };
        self.solved = true;
        self.workspace.solve_with(&problem, reuse)
    }

    /// The workspace, for the answer of the last solve (velocity, multipliers, impulses).
    pub fn workspace(&self) -> &SolverWorkspace {
        self.workspace
    }

    /// The rows this handle solves.
    pub fn rows(&self) -> &Rows {
        self.problem.rows()
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::mass_factor::tests::{random_spd, stream};
    use crate::rows::{RowKind, RowSource, Rows};

    /// The report's residuals (whose stationarity comes from the refinement's last
    /// measurement) equal a fresh evaluation of the answer, with and without refinement.
    fn report_matches_fresh_evaluation(n: usize, m: usize, steps: usize, seed: u64) {
        let mut next = stream(seed);
        let mass = random_spd(n, &mut next);
        let force: Vec<f64> = (0..n).map(|_| 10.0 * next()).collect();
        let mut rows = Rows::new(n);
        for _ in 0..m {
            let row =
                rows.push_zeroed(RowKind::Inequality, RowSource::new(RowTag::new(0), 0), next());
            row.iter_mut().for_each(|c| *c = next());
        }
        let problem = Problem::new(mass.as_ref(), &force, &rows).expect("valid problem");
        let options = SolverOptions { max_refinement_steps: steps, ..SolverOptions::default() };
        let mut workspace = SolverWorkspace::new(options);
        let report = *workspace.solve(&problem).expect("SPD");
        let (mut residual, mut work) = (vec![0.0; n], vec![0.0; n]);
        let (qdot, lambda) = (workspace.velocity(), workspace.multipliers());
        let fresh = Stationarity::measure(&problem, qdot, lambda, None, &mut residual, &mut work);
        let mut residuals = Vec::new();
        row_residuals(&problem, qdot, lambda, None, &mut residuals);
        let evaluation = evaluate(&problem, lambda, fresh, &residuals, options.acceptance);
        assert_eq!(report.residuals, evaluation.residuals);
    }

    proptest! {
        #[test]
        fn reported_residuals_are_those_of_the_answer(
            n in 1usize..=30, m in 0usize..=12, steps in 0usize..=3, seed in any::<u64>()
        ) {
            report_matches_fresh_evaluation(n, m, steps, seed);
        }
    }
}
