//! KKT residuals of an answer (q̇, λ), evaluated against the original data.
//!
//! Row residual vᵢ = cᵢᵀq̇ + εᵢλᵢ − bᵢ (εᵢ = 0 but on compliant rows) with scale
//! sᵢ = 1 + |bᵢ| + Σⱼ|cᵢⱼq̇ⱼ| + |εᵢλᵢ| (the size of the terms that cancel, so vᵢ/sᵢ is the
//! relative accuracy a floating-point answer can reach).
//! Stationarity t = M̃q̇ − f̃ − Cᵀλ with scale 1 + ‖f̃‖∞ + ‖M̃q̇‖∞ + ‖Cᵀλ‖∞. Soft-row slack
//! σᵢ = max(0, −vᵢ). The same evaluation serves the iterative refinement (which drives the
//! free rows' vᵢ and t to rounding level) and the final report, for every backend.

use crate::linalg::norm_max;
use crate::problem::Problem;
use crate::pyramid::{FrictionContact, friction_contacts};
use crate::report::{Residuals, SlackUsage};
use crate::rows::{PerTag, RowKind};

/// vᵢ = cᵢᵀq̇ + εᵢλᵢ − bᵢ and its scale sᵢ = 1 + |bᵢ| + Σⱼ|cᵢⱼq̇ⱼ| + |εᵢλᵢ| (the ε terms
/// only on compliant rows, so other rows are evaluated as without them, bit for bit), summed
/// over the entries
/// `..support` only: cᵢ must vanish from `support` on (n always does; the contact space
/// knows each row's support). For a finite q̇ that is the full sum bit for bit: the partial
/// sums of [`dot_and_magnitude`](crate::linalg::dot_and_magnitude) take entry j in lane j mod 4 either way, and a zero term
/// leaves a lane's sum as it is (a sum of terms from +0 is never −0).
pub(crate) fn row_residual(
    problem: &Problem<'_>,
    row: usize,
    qdot: &[f64],
    lambda: &[f64],
    support: usize,
) -> (f64, f64) {
    let product = problem.rows().coefficients_of(row).dot_and_magnitude(&qdot[..support]);
    residual_of_product(problem, row, lambda, product)
}

/// (vᵢ, sᵢ) of [`row_residual`] from the product cᵢᵀq̇ and its size Σⱼ|cᵢⱼq̇ⱼ| (or a bound on
/// it from above).
fn residual_of_product(
    problem: &Problem<'_>,
    row: usize,
    lambda: &[f64],
    (product, magnitude): (f64, f64),
) -> (f64, f64) {
    let rhs = problem.rhs()[row];
    match problem.rows().kinds()[row].compliance() {
        0.0 => (product - rhs, 1.0 + rhs.abs() + magnitude),
        compliance => {
            let spring = compliance * lambda[row];
            (product + spring - rhs, 1.0 + rhs.abs() + magnitude + spring.abs())
        }
    }
}

/// (vᵢ, sᵢ) of [`row_residual`] for every row, into `out` (m pairs; grow-only): measured once
/// per answer for the primal verification and the report. `supports` holds each row's
/// support (see [`row_residual`]); `None`: every row is summed over all n entries.
pub(crate) fn row_residuals(
    problem: &Problem<'_>,
    qdot: &[f64],
    lambda: &[f64],
    supports: Option<&[usize]>,
    out: &mut Vec<(f64, f64)>,
) {
    out.clear();
    out.extend((0..problem.rows().len()).map(|i| {
        let support = supports.map_or(qdot.len(), |supports| supports[i]);
        row_residual(problem, i, qdot, lambda, support)
    }));
}

/// [`row_residuals`] from the rows' products and their sizes already in `out` (m pairs, e.g.
/// `ContactSpace::row_products`), replaced by (vᵢ, sᵢ).
pub(crate) fn row_residuals_of_products(
    problem: &Problem<'_>,
    lambda: &[f64],
    out: &mut [(f64, f64)],
) {
    for (i, pair) in out.iter_mut().enumerate() {
        *pair = residual_of_product(problem, i, lambda, *pair);
    }
}

/// `residual` ← f̃ + Cᵀλ − M̃q̇ (the negated stationarity residual, the refinement's r₁) using
/// `work` for Cᵀλ; returns the scale 1 + ‖f̃‖∞ + ‖M̃q̇‖∞ + ‖Cᵀλ‖∞. `supports` as for
/// [`row_residuals`].
pub(crate) fn stationarity(
    problem: &Problem<'_>,
    qdot: &[f64],
    lambda: &[f64],
    supports: Option<&[usize]>,
    residual: &mut [f64],
    work: &mut [f64],
) -> f64 {
    problem.apply_mass(qdot, residual);
    transposed_product(problem, lambda, supports, work);
    let scale = 1.0 + norm_max(problem.force()) + norm_max(residual) + norm_max(work);
    for ((t, f), c) in residual.iter_mut().zip(problem.force()).zip(work.iter()) {
        *t = f + c - *t;
    }
    scale
}

/// `out` ← Cᵀλ = Σᵢ λᵢcᵢ, summed row by row over the rows with λᵢ ≠ 0 (most of a friction
/// pyramid's edges are at rest on their bound 0) and each over its entries `..support` (as
/// in [`row_residuals`]): a skipped term would add ±0 to each entry, so the sum is the
/// one over every row and entry, up to the sign of a zero.
fn transposed_product(
    problem: &Problem<'_>,
    lambda: &[f64],
    supports: Option<&[usize]>,
    out: &mut [f64],
) {
    out.fill(0.0);
    let rows = problem.rows();
    for (i, &multiplier) in lambda.iter().enumerate().filter(|&(_, &l)| l != 0.0) {
        let support = supports.map_or(out.len(), |supports| supports[i]);
        rows.coefficients_of(i).add_scaled_to(multiplier, &mut out[..support]);
    }
}

/// The size of the stationarity residual t = M̃q̇ − f̃ − Cᵀλ of an answer: ‖t‖∞ and its
/// scale 1 + ‖f̃‖∞ + ‖M̃q̇‖∞ + ‖Cᵀλ‖∞. The refinement measures it at every step; its last
/// measurement, of the answer it returns, is the report's, so it is not formed twice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stationarity {
    /// ‖t‖∞.
    pub(crate) norm: f64,
    /// 1 + ‖f̃‖∞ + ‖M̃q̇‖∞ + ‖Cᵀλ‖∞.
    pub(crate) scale: f64,
}

impl Stationarity {
    /// Measures (q̇, λ), leaving −t in `residual` (see [`stationarity`]; `work` is scratch).
    pub(crate) fn measure(
        problem: &Problem<'_>,
        qdot: &[f64],
        lambda: &[f64],
        supports: Option<&[usize]>,
        residual: &mut [f64],
        work: &mut [f64],
    ) -> Self {
        let scale = stationarity(problem, qdot, lambda, supports, residual, work);
        Self { norm: norm_max(residual), scale }
    }
}

/// The report's view of an answer: residuals, slack, rows with a non-negligible λ.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Evaluation {
    pub(crate) residuals: Residuals,
    pub(crate) slack: SlackUsage,
    pub(crate) active_per_tag: PerTag<usize>,
}

/// Evaluates an answer (q̇, λ) from λ, its stationarity residual (as
/// [`Stationarity::measure`] gives it) and its row residuals (as [`row_residuals`] gives
/// them); `acceptance` sets the thresholds for "slack used" and "active".
pub(crate) fn evaluate(
    problem: &Problem<'_>,
    lambda: &[f64],
    stationarity: Stationarity,
    row_residuals: &[(f64, f64)],
    acceptance: f64,
) -> Evaluation {
    let mut out = Evaluation {
        residuals: Residuals {
            stationarity: stationarity.norm,
            stationarity_relative: stationarity.norm / stationarity.scale,
            ..Residuals::default()
        },
        ..Evaluation::default()
    };
    let lambda_scale = 1.0 + norm_max(lambda);
    let rows = problem.rows();
    let mut worst = out.residuals.stationarity_relative;
    let each_row = rows.kinds().iter().zip(rows.sources()).zip(row_residuals).zip(lambda);
    for (i, (((&kind, &source), &(v, s)), &l)) in each_row.enumerate() {
        let (primal, dual, complementarity) = match kind {
            RowKind::Equality => (v.abs(), 0.0, 0.0),
            // A cone's normal row: its complementarity is the contact's (below).
            RowKind::Inequality if cone_normal(rows.kinds(), i) => {
                ((-v).max(0.0), (-l).max(0.0), 0.0)
            }
            RowKind::Inequality | RowKind::Compliant { .. } => {
                ((-v).max(0.0), (-l).max(0.0), (l * v).abs())
            }
            // Judged per contact below.
            RowKind::Friction { .. } => (0.0, 0.0, 0.0),
            RowKind::SoftInequality { weight } => {
                let sigma = (-v).max(0.0);
                if sigma > acceptance * s {
                    out.slack.count += 1;
                }
                out.slack.max = out.slack.max.max(sigma);
                let dual = (-l).max(l - weight).max(0.0);
                (0.0, dual, (l * (v + sigma)).abs() + (sigma * (weight - l)).abs())
            }
        };
        worst = worst.max(out.residuals.include((primal, dual, complementarity), s, lambda_scale));
        if l.abs() > acceptance * lambda_scale {
            out.active_per_tag[source.tag] += 1;
        }
    }
    for contact in friction_contacts(rows.kinds()) {
        let (primal, dual, complementarity) = cone_residuals(&contact, lambda, row_residuals);
        let s = contact.rows().map(|i| row_residuals[i].1).fold(0.0, f64::max);
        worst = worst.max(out.residuals.include((primal, dual, complementarity), s, lambda_scale));
    }
    out.residuals.worst_relative = worst;
    out
}

impl Residuals {
    /// Takes one row's (or one friction contact's) primal, dual and complementarity
    /// residuals into the maxima, and returns their worst relative value: primal over the
    /// row's scale `s`, dual over 1 + ‖λ‖∞ (`lambda_scale`), complementarity over both.
    fn include(
        &mut self,
        (primal, dual, complementarity): (f64, f64, f64),
        s: f64,
        lambda_scale: f64,
    ) -> f64 {
        self.primal = self.primal.max(primal);
        self.dual = self.dual.max(dual);
        self.complementarity = self.complementarity.max(complementarity);
        (primal / s).max(dual / lambda_scale).max(complementarity / (s * lambda_scale))
    }
}

/// True when row `i` of `kinds` is a friction cone's normal row (a friction row naming it
/// follows).
fn cone_normal(kinds: &[RowKind], i: usize) -> bool {
    matches!(kinds.get(i + 1), Some(RowKind::Friction { normal, .. }) if *normal == i)
}

/// The cone's residuals of a friction contact (`pyramid.rs`) at multipliers `lambda` and row
/// residuals `row_residuals` ((vᵢ, sᵢ): v_n on the normal row, the slip on the friction
/// rows): primal (μ‖v_t‖ − v_n)⁺, dual (‖λ_t‖ − μλ_n)⁺ and complementarity
/// |λ_n v_n + λ_t·v_t|.
pub(crate) fn cone_residuals(
    contact: &FrictionContact,
    lambda: &[f64],
    row_residuals: &[(f64, f64)],
) -> (f64, f64, f64) {
    let (v_n, l_n) = (row_residuals[contact.normal].0, lambda[contact.normal]);
    let (mut slip, mut force, mut power) = (0.0_f64, 0.0_f64, l_n * v_n);
    for i in contact.tangents() {
        let (v, l) = (row_residuals[i].0, lambda[i]);
        slip = slip.hypot(v);
        force = force.hypot(l);
        power += l * v;
    }
    let mu = contact.coefficient;
    ((mu * slip - v_n).max(0.0), (force - mu * l_n.max(0.0)).max(0.0), power.abs())
}

#[cfg(test)]
mod tests {
    use faer::Mat;
    use proptest::prelude::*;

    use super::*;
    use crate::error::SolverError;
    use crate::mass_factor::tests::stream;
    use crate::rows::{RowSource, RowTag, Rows};

    proptest! {
        /// Summing a row over its support only gives its full residual and scale bit for bit.
        #[test]
        fn supported_row_residual_is_the_full_one(
            n in 1usize..=40, end in 0usize..=40, seed in any::<u64>()
        ) {
            let (mut next, end) = (stream(seed), end.min(n));
            let qdot: Vec<f64> = (0..n).map(|_| 1e3 * next()).collect();
            let mut rows = Rows::new(n);
            let row = rows.push_zeroed(RowKind::Inequality, RowSource::new(RowTag::new(3), 0), next());
            row[..end].iter_mut().for_each(|c| *c = next());
            let mass = Mat::<f64>::identity(n, n);
            let problem = Problem::new(mass.as_ref(), &qdot, &rows).map_err(|e| {
                TestCaseError::fail(e.to_string())
            })?;
            let full = row_residual(&problem, 0, &qdot, &[0.0], n);
            let supported = row_residual(&problem, 0, &qdot, &[0.0], end);
            prop_assert_eq!(full.0.to_bits(), supported.0.to_bits());
            prop_assert_eq!(full.1.to_bits(), supported.1.to_bits());
        }
    }

    #[test]
    fn residuals_of_a_hand_made_answer() -> Result<(), SolverError> {
        // M̃ = I₂, f̃ = (−1, 0); rows: q̇₀ ≥ 0 (wall), q̇₁ + σ ≥ 2 (soft, weight 1).
        let mass = Mat::<f64>::identity(2, 2);
        let mut rows = Rows::new(2);
        rows.push(RowKind::Inequality, RowSource::new(RowTag::new(2), 0), 0.0, &[1.0, 0.0])?;
        let soft = RowKind::SoftInequality { weight: 1.0 };
        rows.push(soft, RowSource::new(RowTag::new(4), 0), 2.0, &[0.0, 1.0])?;
        let problem = Problem::new(mass.as_ref(), &[-1.0, 0.0], &rows)?;
        // Exact answer: q̇ = (0, 1), λ = (1, 1), slack 1 on the soft row.
        let (mut a, mut b, mut rows) = ([0.0; 2], [0.0; 2], Vec::new());
        let mut evaluate = |qdot: &[f64], lambda: &[f64]| {
            let measured = Stationarity::measure(&problem, qdot, lambda, None, &mut a, &mut b);
            row_residuals(&problem, qdot, lambda, None, &mut rows);
            evaluate(&problem, lambda, measured, &rows, 1e-9)
        };
        let exact = evaluate(&[0.0, 1.0], &[1.0, 1.0]);
        assert_eq!(exact.residuals.worst_relative, 0.0);
        assert_eq!(exact.slack, SlackUsage { count: 1, max: 1.0 });
        let active = exact.active_per_tag;
        assert_eq!((active[RowTag::new(2)], active[RowTag::new(4)]), (1, 1));
        assert_eq!(active.iter().map(|(_, n)| n).sum::<usize>(), 2);
        // Penetrating the wall (stationarity still exact).
        let wrong = evaluate(&[-0.5, 1.0], &[0.5, 1.0]);
        assert_eq!(wrong.residuals.primal, 0.5);
        assert_eq!(wrong.residuals.complementarity, 0.25);
        assert_eq!(wrong.residuals.stationarity, 0.0);
        // A soft multiplier above its weight.
        let wrong = evaluate(&[0.0, 2.0], &[1.0, 2.0]);
        assert_eq!(wrong.residuals.dual, 1.0);
        assert_eq!(wrong.slack.count, 0);
        assert!(wrong.residuals.worst_relative > 0.1);
        Ok(())
    }
}
