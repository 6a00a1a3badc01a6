//! Options of the velocity solve: which QP backend, warm starting, tolerances.
//!
//! Tolerances are relative, each measured against the natural scale of its quantity (see
//! [`Residuals`](crate::Residuals)), so the same defaults hold for the hagfish's mix of tiny
//! distal and large proximal inertias (diagonal of M̃ from ~1e-2 to ~1e4 in CGS).

/// Which solver runs the QP path (any inequality row present). The unconstrained and KKT
/// paths always use the Cholesky / Schur-complement machinery.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum QpBackend {
    /// Contact-space dual QP on W = C M̃⁻¹ Cᵀ with a primal active-set method: the fast default.
    #[default]
    ContactSpace,
    /// Clarabel's interior point on the primal QP: the reference judge (slow, allocates).
    Clarabel,
}

/// Where the contact-space active-set method starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WarmStart {
    /// Start from λ = 0 on every inequality (all at their lower bound).
    Cold,
    /// Start from the previous solve's λ (clamped into the current bounds; new rows at 0).
    /// Any feasible start is valid, so this is correct even when rows changed; it saves
    /// iterations when the row order is stable between steps.
    #[default]
    PreviousMultipliers,
}

/// Options of [`SolverWorkspace`](crate::SolverWorkspace).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Backend of the QP path.
    pub backend: QpBackend,
    /// Start of the active-set method.
    pub warm_start: WarmStart,
    /// Cap on active-set iterations (one subproblem solve each); beyond it the status is
    /// `MaxIterations` and the last iterate is returned.
    pub max_iterations: usize,
    /// Relative threshold τ for releasing a row from its bound: a bound is left when its
    /// dual gradient (the row residual cᵢᵀq̇ − bᵢ) is wrong-signed by more than
    /// τ·(1 + |rᵢ| + Σⱼ|Wᵢⱼλⱼ|) during the iteration, or by more than τ·(1 + |bᵢ| + Σⱼ|cᵢⱼq̇ⱼ|)
    /// at the refined answer (the verification).
    pub release_tolerance: f64,
    /// Maximum number of iterative-refinement steps on the final active set.
    pub max_refinement_steps: usize,
    /// The status is `Solved` when every relative residual is at most this.
    pub acceptance: f64,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            backend: QpBackend::ContactSpace,
            warm_start: WarmStart::PreviousMultipliers,
            max_iterations: 1000,
            release_tolerance: 1e-12,
            max_refinement_steps: 5,
            acceptance: 1e-9,
        }
    }
}
