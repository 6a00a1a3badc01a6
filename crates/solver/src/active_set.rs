//! Primal active-set method for the box-constrained dual QP of the contact space.
//!
//! Problem (see `contact_space.rs`): min φ(λ) = ½λᵀWλ − rᵀλ subject to lᵢ ≤ λᵢ ≤ uᵢ, with
//! (l, u) = (−∞, ∞) for equalities, (0, ∞) for inequalities and compliant rows, (0, weight)
//! for soft rows (W holds the compliances εᵢ on its diagonal). Its gradient g = Wλ − r is the
//! vector of row residuals Cq̇ + Eλ − b.
//!
//! Only bounds constrain λ, so the working set is simply which variables sit at a bound; F
//! holds the rest (the equalities and the rows in contact), kept linearly independent so that
//! W_FF is positive definite. Each iteration:
//!
//! 1. Subproblem on F with the bounded variables fixed:
//!    W_FF λ_F* = r_F − Σ_{j at upper} W_Fj uⱼ, via the updated factor (`free_set.rs`).
//! 2. Ratio test along p = λ_F* − λ_F: the largest α ≤ 1 keeping every λᵢ in [lᵢ, uᵢ]. If a
//!    bound blocks (α < 1), step there, fix that variable at the bound, drop it from F.
//! 3. Otherwise λ_F = λ_F* is optimal for this working set. A variable at its lower bound is
//!    optimal when gᵢ ≥ 0 (the row is satisfied), at its upper bound when gᵢ ≤ 0 (the soft
//!    row needs its slack). If some gᵢ is wrong-signed by more than τ(1 + |rᵢ| + Σⱼ|Wᵢⱼλⱼ|)
//!    (τ = `release_tolerance`), release the worst one (largest |gᵢ|/√Wᵢᵢ: the most violated
//!    row in the M̃⁻¹ metric); else stop: λ is optimal.
//! 4. Release of row i: it joins F if cᵢ is independent of c_F (the pivot of the factor
//!    update exceeds `DEPENDENCE`·Wᵢᵢ); dependent rows are swapped in along a null direction
//!    of W, or prove the hard rows infeasible (`release.rs`). When the worst row simply
//!    joined, the other wrong-signed rows follow it into F in order of violation while each
//!    is independent of F: a join leaves λ, and so their gradients, as they were, and each
//!    added row's gᵢ < 0 keeps the step to the new subproblem's minimum a descent direction.
//!    One gradient then serves many releases (on Choi et al.'s 9₁, whose first solve of a
//!    step changes ≈ 100 of ≈ 150 free pyramid edges, it cut the solve by ≈ 30 %); the
//!    first dependent row waits for a fresh gradient.
//! 5. Verification (driven by the workspace after refinement): bound rows are checked
//!    against the refined primal residual, which is more accurate than the dual gradient
//!    when large multipliers cancel, and a violated one resumes the iteration
//!    (`verification.rs`).
//!
//! Each step lowers φ (strictly, unless degenerate), so the method terminates; degenerate
//! cycling is cut off by `max_iterations`. The answer is exact up to rounding: bounded
//! multipliers sit exactly on their bound (exact complementarity) and the free rows hold as
//! equalities. Cost per iteration is O(m·|F|): it scales with the rows in contact, not with
//! m³ per iteration as an interior point would.
//!
//! Equalities start in F (only a pivot at rounding level counts as dependent for them: a
//! nearly dependent equality is still a constraint); one dependent on earlier equalities is
//! set aside as redundant (λ = 0, never freed) and checked at the refined q̇: violated there,
//! the equalities contradict each other. Warm start: any λ inside the box is a valid start; the
//! previous step's λ (clamped) puts the previous contacts straight into F, a row dependent on
//! those before it handing its impulse over to them (decision 0033).

use std::sync::atomic::{AtomicBool, Ordering};

mod release;
mod verification;

use release::Release;

use crate::contact_space::{ContactSpace, ReducedScratch};
use crate::error::SolverError;
use crate::free_set::FreeSet;
use crate::linalg::{Entries, try_capacity, zeroed};
use crate::rows::RowKind;

/// A row counts as linearly dependent on F when its pivot is below this fraction of Wᵢᵢ
/// (sine of the angle to span(c_F) in the M̃⁻¹ metric below ~3e-5). Exact dependencies show
/// pivots ≲ 1e-12 after rounding, genuinely distinct rows ≳ 1e-6.
const DEPENDENCE: f64 = 1e-9;

/// Pivots below this fraction of W_rr are the rounding of an exact dependence (no curvature;
/// a row with such a pivot is never factored).
const ROUNDING: f64 = 1e-12;

/// Where a multiplier sits relative to its box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Bound {
    Free,
    Lower,
    Upper,
    /// An equality implied by the other equalities: λ = 0, never freed.
    Redundant,
}

/// Outcome of trying to add a row to F.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Join {
    /// The row was independent and is now free.
    Joined,
    /// The row is (nearly) in span(c_F); its pivot d² = W_rr − lᵀl (≈ 0).
    Dependent { pivot: f64 },
}

/// Limits of one active-set run.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ActiveSetLimits<'a> {
    /// Maximum number of subproblem solves.
    pub(crate) max_iterations: usize,
    /// Relative release threshold τ.
    pub(crate) release_tolerance: f64,
    /// Once set, the run ends before its next iteration ([`Termination::Stopped`]).
    pub(crate) stop: Option<&'a AtomicBool>,
}

/// Why an active-set run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Termination {
    /// λ is optimal.
    Optimal,
    /// `max_iterations` was reached; λ is the last (box-feasible) iterate.
    MaxIterations,
    /// A Farkas ray: the hard rows are infeasible.
    Infeasible,
    /// The stop flag of [`ActiveSetLimits`] was set; λ is the last iterate.
    Stopped,
}

/// How an active-set run ended and after how many subproblem solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ActiveSetOutcome {
    /// Subproblem solves performed.
    pub(crate) iterations: usize,
    /// Why the run stopped.
    pub(crate) termination: Termination,
}

/// State and scratch of the active-set method (all buffers grow-only).
#[derive(Debug, Default)]
pub(crate) struct ActiveSet {
    bound: Vec<Bound>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    free: FreeSet,
    compact: Vec<f64>,
    border: Vec<f64>,
    z: Vec<f64>,
    gradient: Vec<f64>,
    magnitude: Vec<f64>,
    /// Σ dⱼ L⁻¹cⱼ of a dependent release's direction (n).
    ray: Vec<f64>,
    /// z + Yλ = Lᵀq̇(λ) (n).
    lift: Vec<f64>,
    /// (row, λ) before a tentative dependent-release step, to undo it.
    saved: Vec<(usize, f64)>,
    /// Rows whose release was found implied by F, with the F version they were found at.
    implied: Vec<usize>,
    /// Incremented whenever F changes (so `implied` marks expire).
    version: usize,
    /// The warm-started rows in the order they join F.
    warm: Vec<usize>,
    /// The rows at their upper bound, in row order (gathered for each subproblem).
    at_upper: Vec<usize>,
    /// Scratch of the dual gradient.
    reduced: ReducedScratch,
    /// The bound rows whose gradient is wrong-signed, most violated first, with their scores.
    violated: Vec<(usize, f64)>,
    /// The rows released in the last iteration.
    released: Vec<usize>,
}

impl ActiveSet {
    /// Reserves room for problems of up to `dofs` velocities and `rows` rows.
    pub(crate) fn try_reserve(&mut self, dofs: usize, rows: usize) -> Result<(), SolverError> {
        try_capacity(&mut self.bound, rows, "the active set's bounds")?;
        for buffer in [
            &mut self.lower,
            &mut self.upper,
            &mut self.compact,
            &mut self.border,
            &mut self.z,
            &mut self.gradient,
            &mut self.magnitude,
        ] {
            try_capacity(buffer, rows, "an active-set row vector")?;
        }
        try_capacity(&mut self.ray, dofs, "the active set's ray")?;
        try_capacity(&mut self.lift, dofs, "the active set's lift")?;
        self.free.try_reserve(rows)?;
        self.free.reset(rows);
        try_capacity(&mut self.saved, rows + 1, "the active set's saved multipliers")?;
        for buffer in [&mut self.implied, &mut self.warm, &mut self.at_upper, &mut self.released] {
            try_capacity(buffer, rows, "an active-set index")?;
        }
        try_capacity(&mut self.violated, rows, "the active set's violated rows")?;
        self.reduced.try_reserve(rows)
    }

    /// The free rows and their factor at the end of the last run (for refinement).
    pub(crate) fn free(&self) -> &FreeSet {
        &self.free
    }

    /// Minimises the dual from the start `lambda` (clamped into the box; non-finite entries
    /// become 0) and leaves the minimiser in `lambda`.
    pub(crate) fn solve(
        &mut self,
        dual: &ContactSpace,
        kinds: &[RowKind],
        lambda: &mut [f64],
        limits: ActiveSetLimits<'_>,
    ) -> ActiveSetOutcome {
        let end = |iterations, termination| ActiveSetOutcome { iterations, termination };
        self.start(dual, kinds, lambda);
        if kinds.is_empty() {
            return end(0, Termination::Optimal);
        }
        self.iterate(dual, lambda, limits)
    }

    /// Steps 1–4 until optimal, infeasible or out of iterations.
    fn iterate(
        &mut self,
        dual: &ContactSpace,
        lambda: &mut [f64],
        limits: ActiveSetLimits<'_>,
    ) -> ActiveSetOutcome {
        let end = |iterations, termination| ActiveSetOutcome { iterations, termination };
        self.released.clear();
        for iteration in 1..=limits.max_iterations {
            if limits.stop.is_some_and(|flag| flag.load(Ordering::Relaxed)) {
                return end(iteration - 1, Termination::Stopped);
            }
            self.solve_subproblem(dual);
            if let Some((row, alpha)) = self.step_to_subproblem_minimum(lambda) {
                // A row released and blocked again without moving made no progress.
                if alpha == 0.0 && self.released.contains(&row) {
                    self.implied[row] = self.version;
                }
                self.released.clear();
                continue;
            }
            self.released.clear();
            if !self.find_violated_bounds(dual, lambda, limits.release_tolerance) {
                return end(iteration, Termination::Optimal);
            }
            let worst = self.violated[0].0;
            match self.release(dual, lambda, worst) {
                Release::Infeasible => return end(iteration, Termination::Infeasible),
                Release::Resolved => self.released.push(worst),
                Release::Joined => self.join_violated(dual),
            }
        }
        end(limits.max_iterations, Termination::MaxIterations)
    }

    /// Bounds from the row kinds, a feasible start, and the factor of the initial F.
    fn start(&mut self, dual: &ContactSpace, kinds: &[RowKind], lambda: &mut [f64]) {
        let m = kinds.len();
        self.lower.clear();
        self.upper.clear();
        self.bound.clear();
        for (value, kind) in lambda.iter_mut().zip(kinds) {
            let (lower, upper) = match *kind {
                RowKind::Equality => (f64::NEG_INFINITY, f64::INFINITY),
                RowKind::Inequality | RowKind::Compliant { .. } => (0.0, f64::INFINITY),
                RowKind::SoftInequality { weight } => (0.0, weight),
                // Never here: the workspace refuses friction cones on this path
                // (`SolverError::FrictionConeNeedsClarabel`); held at 0 if it were.
                RowKind::Friction { .. } => (0.0, 0.0),
            };
            let start = if value.is_finite() { *value } else { 0.0 };
            let bound = if start <= lower {
                Bound::Lower
            } else if start >= upper {
                Bound::Upper
            } else {
                Bound::Free
            };
            *value = start.clamp(lower, upper);
            self.lower.push(lower);
            self.upper.push(upper);
            self.bound.push(bound);
        }
        for buffer in [
            &mut self.compact,
            &mut self.border,
            &mut self.z,
            &mut self.gradient,
            &mut self.magnitude,
        ] {
            zeroed(buffer, m);
        }
        zeroed(&mut self.ray, dual.dofs());
        zeroed(&mut self.lift, dual.dofs());
        self.saved.clear();
        self.saved.reserve(m + 1);
        self.implied.clear();
        self.implied.resize(m, usize::MAX);
        self.warm.clear();
        self.warm.extend(
            (0..m).filter(|&i| kinds[i] != RowKind::Equality && self.bound[i] == Bound::Free),
        );
        self.join_equalities(dual, kinds, lambda);
        // A warm row that depends on the rows already in F hands its impulse to them, so that
        // the start keeps Cᵀλ, the previous answer's q̇ (`release.rs`, `hand_over`). Left at
        // its bound with its impulse dropped instead, a degenerate vertex (more rows in
        // contact than DOFs) was re-solved from its own answer in more iterations than from
        // λ = 0 (cases of tests/integration/random_problems.rs, kept as regressions).
        for k in 0..self.warm.len() {
            let row = self.warm[k];
            if self.try_join(dual, row, DEPENDENCE) != Join::Joined {
                self.hand_over(dual, lambda, row);
            }
        }
    }

    /// Starts F afresh with the equalities; one dependent on earlier ones (a pivot at rounding
    /// level) is set aside as redundant with λ = 0.
    fn join_equalities(&mut self, dual: &ContactSpace, kinds: &[RowKind], lambda: &mut [f64]) {
        self.free.reset(kinds.len());
        self.version = 0;
        for row in (0..kinds.len()).filter(|&i| kinds[i] == RowKind::Equality) {
            if self.bound[row] != Bound::Redundant
                && self.try_join(dual, row, ROUNDING) == Join::Joined
            {
                continue;
            }
            self.bound[row] = Bound::Redundant;
            lambda[row] = 0.0;
        }
    }

    /// Adds `row` to F if it is independent of it (pivot > `threshold`·W_rr); otherwise
    /// leaves z with c_row ≈ Σ_p z_p c_p in `self.z[..|F|]`, its border in `self.border`,
    /// and returns the pivot.
    fn try_join(&mut self, dual: &ContactSpace, row: usize, threshold: f64) -> Join {
        let k = self.free.indices().len();
        let pivot = self.free.border(dual, row, &mut self.border);
        if pivot > threshold * dual.entry(row, row) {
            self.join(row, pivot);
            return Join::Joined;
        }
        self.z[..k].copy_from_slice(&self.border[..k]);
        self.free.backward(&mut self.z[..k]);
        Join::Dependent { pivot }
    }

    /// Appends `row` to F with the border in `self.border` and its (positive) pivot.
    fn join(&mut self, row: usize, pivot: f64) {
        self.free.push(row, &self.border, pivot);
        self.bound[row] = Bound::Free;
        self.version += 1;
    }

    /// `compact` ← λ_F* = W_FF⁻¹(r_F − Σ_{j at upper} W_Fj uⱼ), in factor order.
    fn solve_subproblem(&mut self, dual: &ContactSpace) {
        let r = dual.r();
        let f = self.free.indices().len();
        self.at_upper.clear();
        self.at_upper.extend((0..self.bound.len()).filter(|&j| self.bound[j] == Bound::Upper));
        for (target, &i) in self.compact.iter_mut().zip(self.free.indices()) {
            let fixed: f64 = self.at_upper.iter().map(|&j| dual.entry(i, j) * self.upper[j]).sum();
            *target = r[i] - fixed;
        }
        self.free.solve(&mut self.compact[..f]);
    }

    /// Moves λ_F toward the subproblem minimum; when a bound blocks the step, fixes that
    /// variable at the bound, removes it from F and returns it with the step fraction α.
    fn step_to_subproblem_minimum(&mut self, lambda: &mut [f64]) -> Option<(usize, f64)> {
        let mut alpha = 1.0;
        let mut blocking = None;
        for (position, (&i, &target)) in self.free.indices().iter().zip(&self.compact).enumerate() {
            let step = target - lambda[i];
            let (limit, side) = if step < 0.0 {
                (self.lower[i], Bound::Lower)
            } else {
                (self.upper[i], Bound::Upper)
            };
            if limit.is_finite() && (target - limit) * step > 0.0 {
                let fraction = ((limit - lambda[i]) / step).max(0.0);
                if fraction < alpha {
                    alpha = fraction;
                    blocking = Some((position, side));
                }
            }
        }
        for (&i, &target) in self.free.indices().iter().zip(&self.compact) {
            lambda[i] = match blocking {
                None => target,
                Some(_) => lambda[i] + alpha * (target - lambda[i]),
            };
        }
        let (position, side) = blocking?;
        let row = self.free.remove(position);
        self.version += 1;
        self.fix(lambda, row, side);
        Some((row, alpha))
    }

    /// Fills `violated` with the bounded variables whose dual gradient is wrong-signed beyond
    /// the threshold, most violated first (by |gᵢ|/√Wᵢᵢ, then by row), and says whether there
    /// is any.
    fn find_violated_bounds(
        &mut self,
        dual: &ContactSpace,
        lambda: &[f64],
        tolerance: f64,
    ) -> bool {
        dual.gradient(lambda, &mut self.reduced, &mut self.gradient, &mut self.magnitude);
        self.violated.clear();
        for i in 0..lambda.len() {
            if self.implied[i] == self.version {
                continue;
            }
            let violation = match self.bound[i] {
                Bound::Free | Bound::Redundant => continue,
                Bound::Lower => -self.gradient[i],
                Bound::Upper => self.gradient[i],
            };
            if violation > tolerance * (1.0 + self.magnitude[i]) {
                self.violated.push((i, violation / dual.entry(i, i).sqrt()));
            }
        }
        self.violated.sort_unstable_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        !self.violated.is_empty()
    }

    /// After the most violated row joined F without moving λ (step 4), the other violated
    /// rows in order join F too while each is independent of it: a join leaves λ as it is, so
    /// their gradients still hold; the first dependent one is left for a later iteration,
    /// whose gradient is fresh (its release may move λ). Remembers the rows released.
    fn join_violated(&mut self, dual: &ContactSpace) {
        self.released.push(self.violated[0].0);
        for k in 1..self.violated.len() {
            let row = self.violated[k].0;
            if self.try_join(dual, row, DEPENDENCE) != Join::Joined {
                break;
            }
            self.released.push(row);
        }
    }

    /// Puts `row` exactly on its `side` bound.
    fn fix(&mut self, lambda: &mut [f64], row: usize, side: Bound) {
        self.bound[row] = side;
        lambda[row] = match side {
            Bound::Upper => self.upper[row],
            _ => self.lower[row],
        };
    }
}
