//! What a solve reports: the path taken, the outcome and the quality of the answer.
//!
//! The outcome is a [`SolveStatus`], never a panic or a bare `bool`. The [`Residuals`] are
//! recomputed from the returned q̇ and λ against the original data, for every path and
//! backend alike, so they are an independent check of the KKT conditions
//! M̃q̇ = f̃ + Cᵀλ, Gq̇ = b_G, Cq̇ ≥ b_C, λ_C ≥ 0, λᵢ(cᵢᵀq̇ − bᵢ) = 0.

use crate::options::QpBackend;
use crate::rows::PerTag;

/// Which system was solved; chosen by the rows present.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SolvePath {
    /// No rows: M̃q̇ = f̃ by Cholesky.
    #[default]
    Unconstrained,
    /// Equality rows only: KKT system by the Schur complement W = G M̃⁻¹ Gᵀ.
    Kkt,
    /// At least one (soft) inequality: the QP, by the [`QpBackend`] in the report.
    Qp,
}

/// Outcome of a solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SolveStatus {
    /// Every relative residual is within `SolverOptions::acceptance`.
    #[default]
    Solved,
    /// The method finished, but some relative residual exceeds the acceptance (the answer is
    /// usable with care; see the residuals).
    SolvedInexact,
    /// The active-set (or clarabel) iteration cap was hit; q̇ and λ are the last iterate.
    MaxIterations,
    /// The hard rows contradict each other: a Farkas ray y (Σyᵢcᵢ = 0, yᵀb > 0, y ≥ 0 on
    /// inequalities) was found, or contradictory equalities; q̇ and λ are the last iterate.
    Infeasible,
    /// Non-finite numbers appeared during the solve, or the backend gave up numerically.
    NumericalError,
}

impl SolveStatus {
    /// True for `Solved` and `SolvedInexact`: q̇ solves the problem (to the reported accuracy).
    pub fn is_solved(self) -> bool {
        matches!(self, SolveStatus::Solved | SolveStatus::SolvedInexact)
    }
}

/// Residuals of the KKT conditions at the returned (q̇, λ). Absolute values are in the
/// problem's units; the relative ones divide by the natural scale of each quantity.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Residuals {
    /// Primal feasibility: max over equalities |cᵢᵀq̇ − bᵢ| and hard inequalities
    /// max(0, bᵢ − cᵢᵀq̇) (soft rows are feasible through their slack).
    pub primal: f64,
    /// Dual feasibility: max violation of λ ≥ 0 (inequalities) and 0 ≤ λ ≤ weight (soft).
    pub dual: f64,
    /// Complementarity: max |λᵢ(cᵢᵀq̇ − bᵢ)| on hard inequalities and
    /// |λᵢ(cᵢᵀq̇ + σᵢ − bᵢ)| + |σᵢ(weightᵢ − λᵢ)| on soft ones.
    pub complementarity: f64,
    /// Stationarity: ‖M̃q̇ − f̃ − Cᵀλ‖∞.
    pub stationarity: f64,
    /// ‖M̃q̇ − f̃ − Cᵀλ‖∞ / (1 + ‖f̃‖∞ + ‖M̃q̇‖∞ + ‖Cᵀλ‖∞).
    pub stationarity_relative: f64,
    /// Largest relative residual of all four kinds: row residuals over 1 + |bᵢ| + Σⱼ|cᵢⱼq̇ⱼ|,
    /// multiplier violations over 1 + ‖λ‖∞. Compared against the acceptance.
    pub worst_relative: f64,
}

/// How much of the soft rows' slack was needed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SlackUsage {
    /// Soft rows whose slack σᵢ = max(0, bᵢ − cᵢᵀq̇) is above the acceptance (their λ sits at
    /// the weight: the target could not be met).
    pub count: usize,
    /// Largest slack σᵢ (velocity units, cm/s for point rows).
    pub max: f64,
}

/// Everything a caller needs to judge a solve (see [`SolveStatus`] first).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolveReport {
    /// Which system was solved.
    pub path: SolvePath,
    /// The QP backend, when the path is [`SolvePath::Qp`].
    pub backend: Option<QpBackend>,
    /// The outcome.
    pub status: SolveStatus,
    /// Iterations: active-set subproblem solves (1 on the KKT path, 0 unconstrained), or
    /// clarabel's interior-point iterations.
    pub iterations: usize,
    /// Iterative-refinement steps applied on the final active set (contact-space machinery).
    pub refinement_steps: usize,
    /// True when the active-set method started from the previous multipliers.
    pub warm_started: bool,
    /// Number of rows per [`RowTag`](crate::RowTag).
    pub rows_per_tag: PerTag<usize>,
    /// Rows with a non-negligible multiplier (|λᵢ| > acceptance·(1 + ‖λ‖∞)) per tag.
    pub active_per_tag: PerTag<usize>,
    /// KKT residuals at the answer.
    pub residuals: Residuals,
    /// Slack used by the soft rows.
    pub slack: SlackUsage,
    /// Rows of Y_R = L⁻¹C_Rᵀ that the contact space's Gram product W_R = Y_RᵀY_R left out:
    /// the DOF ranges between the rows' breaks, each replaced by at most six coordinates in
    /// its wrench span (`contact_space/compressed_spans.rs`); 0 on other paths or with no
    /// range to compress.
    pub gram_rows_saved: usize,
}
