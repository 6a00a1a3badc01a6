//! Compliant rows (`RowKind::Compliant`, an implicit spring `cᵀq̇ + ελ ≥ b`): a hand-solved
//! skin over a hard core, and random problems with compliant rows added, against the KKT
//! conditions and clarabel (whose compliant rows are a quadratic slack cost, an independent
//! formulation).

use crate::common::{Rng, Scenario, Shape, random_mass, random_row, scenario};
use crate::random_problems::{Outcome, check_kkt, dot, mass_times, solve};
use faer::Mat;
use hagfish_solver::{
    Problem, QpBackend, RowKind, RowSource, RowTag, Rows, SolveStatus, SolverError, SolverOptions,
    SolverWorkspace,
};
use proptest::prelude::*;

const SKIN: RowTag = RowTag::new(5);
const CORE: RowTag = RowTag::new(3);

/// One DOF of unit mass pushed by f̃ = −1 into a skin (q̇ + λ ≥ 0, ε = 1) over a core
/// (q̇ ≥ `core`): without the core the spring stops half the push (λ = ½, q̇ = −½); a core
/// at −¼ takes the rest (q̇ = −¼, the skin λ = ¼, the core λ = ½).
#[test]
fn a_skin_over_a_core_shares_the_push_as_solved_by_hand() -> Result<(), SolverError> {
    for (backend, tolerance) in [(QpBackend::ContactSpace, 1e-14), (QpBackend::Clarabel, 1e-8)] {
        let mass = Mat::<f64>::identity(1, 1);
        let mut rows = Rows::new(1);
        rows.push(RowKind::Compliant { compliance: 1.0 }, RowSource::new(SKIN, 0), 0.0, &[1.0])?;
        let mut workspace = SolverWorkspace::new(SolverOptions { backend, ..Default::default() });
        workspace.solve(&Problem::new(mass.as_ref(), &[-1.0], &rows)?)?;
        let (qdot, lambda) = (workspace.velocity()[0], workspace.multipliers()[0]);
        assert!((qdot + 0.5).abs() < tolerance && (lambda - 0.5).abs() < tolerance, "{backend:?}");

        rows.push(RowKind::Inequality, RowSource::new(CORE, 0), -0.25, &[1.0])?;
        let report = *workspace.solve(&Problem::new(mass.as_ref(), &[-1.0], &rows)?)?;
        assert_eq!(report.status, SolveStatus::Solved, "{backend:?}");
        let (qdot, lambda) = (workspace.velocity()[0], workspace.multipliers());
        assert!((qdot + 0.25).abs() < tolerance, "{backend:?}: q̇ = {qdot}");
        assert!((lambda[0] - 0.25).abs() < tolerance, "{backend:?}: skin λ = {}", lambda[0]);
        assert!((lambda[1] - 0.5).abs() < tolerance, "{backend:?}: core λ = {}", lambda[1]);
    }
    Ok(())
}

/// A zero or negative compliance is refused when the problem is built.
#[test]
fn a_compliance_must_be_positive() -> Result<(), SolverError> {
    let mass = Mat::<f64>::identity(1, 1);
    for compliance in [0.0, -1.0, f64::NAN] {
        let mut rows = Rows::new(1);
        rows.push(RowKind::Compliant { compliance }, RowSource::new(SKIN, 0), 0.0, &[1.0])?;
        let built = Problem::new(mass.as_ref(), &[0.0], &rows);
        assert!(matches!(built, Err(SolverError::InvalidCompliance { row: 0, .. })), "{built:?}");
    }
    Ok(())
}

/// The compliances drawn for the added rows: relative to the row's own mobility cᵀM̃⁻¹c (a
/// skin's ε/(cᵀM̃⁻¹c) = m_eff/(k h²) is ≈ 0.3–3 on ES103 at h = 0.01 s, ×100 at h = 0.001 s), or
/// relative to |c|² alone, which on the random masses (diagonal 1e-2 … 1e2) reaches
/// ε ≈ 1e-7·cᵀM̃⁻¹c: a nearly rigid row whose pivot εᵢ cancels against Wᵢᵢ.
#[derive(Clone, Copy, Debug)]
enum Compliance {
    /// ε = cᵀM̃⁻¹c × [1e-3, 10].
    Mobility,
    /// ε = [1e-3, 10] / (1 + |c|²).
    RowNorm,
}

/// cᵀM̃⁻¹c, by the solver's unconstrained path (M̃q̇ = c).
fn mobility(mass: &Mat<f64>, c: &[f64]) -> f64 {
    let rows = Rows::new(c.len());
    let mut workspace = SolverWorkspace::new(SolverOptions::default());
    let solved =
        Problem::new(mass.as_ref(), c, &rows).and_then(|p| workspace.solve(&p).map(|_| ()));
    assert!(solved.is_ok(), "an SPD mass: {solved:?}");
    dot(c, workspace.velocity())
}

/// A random problem of `shape` with `compliant` compliant rows added: each a skin over one of
/// the hard inequalities when there are some (its c scaled, its bound raised: it engages
/// before the hard row) or a random row, its ε drawn as `compliance` says.
fn with_compliant_rows(
    shape: Shape,
    compliant: usize,
    compliance: Compliance,
    seed: u64,
) -> Scenario {
    let mut rng = Rng::new(seed);
    let mass = random_mass(&mut rng, shape.dofs);
    let mut s = scenario(&mut rng, mass, shape);
    let hard: Vec<usize> =
        (0..s.rows.len()).filter(|&i| s.rows.kinds()[i] == RowKind::Inequality).collect();
    for k in 0..compliant {
        let (row, rhs) = if !hard.is_empty() && rng.uniform() < 0.5 {
            let original = hard[rng.below(hard.len())];
            let c = s.rows.row(original).map(|r| r.to_vec()).unwrap_or_default().to_vec();
            let raised = s.rows.rhs()[original] + rng.uniform() * dot(&c, &c).sqrt();
            (c, raised)
        } else {
            let c = random_row(&mut rng, shape.dofs);
            let rhs = rng.normal() * dot(&c, &c).sqrt();
            (c, rhs)
        };
        let scale = match compliance {
            Compliance::Mobility => mobility(&s.mass, &row),
            Compliance::RowNorm => 1.0 / (1.0 + dot(&row, &row)),
        };
        let kind = RowKind::Compliant { compliance: scale * rng.log_uniform(1e-3, 10.0) };
        let pushed = s.rows.push(kind, RowSource::new(SKIN, 1000 + k), rhs, &row);
        assert!(pushed.is_ok(), "generator built a row of the wrong length");
    }
    s
}

fn compliant_problem_matches_clarabel(shape: Shape, compliant: usize, seed: u64) -> Outcome {
    let s = with_compliant_rows(shape, compliant, Compliance::Mobility, seed);
    let (report, fast, lambda) = solve(&s, QpBackend::ContactSpace)?;
    prop_assert_eq!(report.status, SolveStatus::Solved);
    check_kkt(&s, &fast, &lambda)?;
    let (reference_report, reference, _) = solve(&s, QpBackend::Clarabel)?;
    if matches!(reference_report.status, SolveStatus::Solved | SolveStatus::SolvedInexact) {
        let difference: Vec<f64> = fast.iter().zip(&reference).map(|(a, b)| a - b).collect();
        let m_norm = |x: &[f64]| dot(x, &mass_times(&s, x)).max(0.0).sqrt();
        let error = m_norm(&difference) / (m_norm(&reference) + 1e-3);
        let (judge, ours) =
            (reference_report.residuals.worst_relative, report.residuals.worst_relative);
        prop_assert!(error < 1e-6 || judge > 100.0 * ours, "gap {error:e}: {judge:e} vs {ours:e}");
    }
    Ok(())
}

/// Nearly rigid compliant rows (ε down to ≈ 1e-7 of their mobility) on rows dependent on
/// others lose digits in the pivot εᵢ (W_FF's `cᵀM̃⁻¹c + ε − cᵀM̃⁻¹c`): the answer must then be
/// reported `SolvedInexact` rather than passed off, and a `Solved` one must satisfy the KKT
/// conditions (1 DOF, 35 inequalities and 6 compliant rows in `compliant_rows.txt` gave a
/// stationarity of 1e-8 relative, reported inexact).
fn nearly_rigid_rows_are_reported_honestly(shape: Shape, compliant: usize, seed: u64) -> Outcome {
    let s = with_compliant_rows(shape, compliant, Compliance::RowNorm, seed);
    let (report, qdot, lambda) = solve(&s, QpBackend::ContactSpace)?;
    let expected = [SolveStatus::Solved, SolveStatus::SolvedInexact];
    prop_assert!(expected.contains(&report.status), "{:?}", report);
    if report.status == SolveStatus::Solved {
        check_kkt(&s, &qdot, &lambda)?;
    }
    Ok(())
}

/// Shapes up to n = 60 with up to 40 inequalities, 2 soft rows and 12 compliant rows: the shape,
/// the number of compliant rows and the seed (drawn in the order the tests' arguments were).
fn shapes() -> impl Strategy<Value = (Shape, usize, u64)> {
    (1usize..=60, 0usize..=40, 0usize..=2, 1usize..=12, any::<u64>()).prop_map(
        |(dofs, inequalities, soft, compliant, seed)| {
            let tight = (0.5 * dofs as f64 / inequalities.max(1) as f64).min(0.5);
            let equalities = dofs.min(2);
            (
                Shape { dofs, equalities, inequalities, soft, duplicates: 0.1, tight },
                compliant,
                seed,
            )
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The contact-space answer with compliant rows satisfies the KKT conditions (the
    /// compliant rows' `Cq̇ + ελ − b ≥ 0 ⟂ λ ≥ 0`) and agrees with clarabel.
    #[test]
    fn compliant_rows_satisfy_kkt_and_match_clarabel((shape, compliant, seed) in shapes()) {
        compliant_problem_matches_clarabel(shape, compliant, seed)?;
    }

    /// See [`nearly_rigid_rows_are_reported_honestly`].
    #[test]
    fn nearly_rigid_compliant_rows_are_solved_or_reported_inexact(
        (shape, compliant, seed) in shapes()
    ) {
        nearly_rigid_rows_are_reported_honestly(shape, compliant, seed)?;
    }
}
