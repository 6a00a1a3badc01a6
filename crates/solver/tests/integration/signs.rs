//! Hand-checked signs and outcomes on tiny problems, for both QP backends.
//!
//! Convention under test: M̃q̇ = f̃ + Cᵀλ, a row that stops motion gets λ > 0, soft rows report
//! their slack, infeasible hard rows give status Infeasible (never a panic).

use faer::{Mat, mat};
use hagfish_solver::{
    Problem, QpBackend, RowKind, RowSource, RowTag, Rows, SolvePath, SolveReport, SolveStatus,
    SolverError, SolverOptions, SolverWorkspace,
};

/// The tests' own row kinds (the solver interprets none of them).
const FIXED: RowTag = RowTag::new(0);
const LIMIT: RowTag = RowTag::new(1);
const WALL: RowTag = RowTag::new(2);
const CONTACT: RowTag = RowTag::new(3);
const TARGET: RowTag = RowTag::new(4);

const BACKENDS: [QpBackend; 2] = [QpBackend::ContactSpace, QpBackend::Clarabel];

fn solve(
    mass: &Mat<f64>,
    force: &[f64],
    rows: &Rows,
    backend: QpBackend,
) -> Result<(SolveReport, Vec<f64>, Vec<f64>, SolverWorkspace), SolverError> {
    let problem = Problem::new(mass.as_ref(), force, rows)?;
    let mut ws = SolverWorkspace::new(SolverOptions { backend, ..SolverOptions::default() });
    let report = *ws.solve(&problem)?;
    let (qdot, lambda) = (ws.velocity().to_vec(), ws.multipliers().to_vec());
    Ok((report, qdot, lambda, ws))
}

/// 1 DOF pushed into the wall: f̃ = −2 (toward negative velocity), row q̇ ≥ 0 → q̇ = 0,
/// λ = 2 > 0, and the wall's generalized impulse is +2.
#[test]
fn body_pushed_into_the_wall_stops_with_positive_multiplier() -> Result<(), SolverError> {
    let mass = mat![[0.5]];
    let mut rows = Rows::new(1);
    rows.push(RowKind::Inequality, RowSource::new(WALL, 0), 0.0, &[1.0])?;
    for backend in BACKENDS {
        let (report, qdot, lambda, ws) = solve(&mass, &[-2.0], &rows, backend)?;
        assert!(report.status.is_solved(), "{backend:?}: {report:?}");
        assert_eq!((report.path, report.backend), (SolvePath::Qp, Some(backend)));
        assert!(
            qdot[0].abs() < 1e-8 && (lambda[0] - 2.0).abs() < 1e-7,
            "{backend:?}: {qdot:?} {lambda:?}"
        );
        assert!((ws.tag_impulse(WALL)[0] - 2.0).abs() < 1e-7);
        assert_eq!(ws.tag_impulse(CONTACT), &[0.0]);
        assert_eq!(report.active_per_tag.iter().map(|(_, n)| n).sum::<usize>(), 1);
        assert_eq!(report.active_per_tag[WALL], 1);
    }
    Ok(())
}

/// Upper joint limit as −eₖᵀq̇ ≥ b with b = −0.5 (q̇ₖ ≤ 0.5). M̃ = I₂, f̃ = (3, 1): DOF 0 hits the
/// limit (q̇₀ = 0.5, λ = 2.5 > 0, impulse −2.5 on DOF 0), DOF 1 is untouched (q̇₁ = 1).
#[test]
fn upper_limit_row_is_hit_and_pushes_back() -> Result<(), SolverError> {
    let mass = Mat::<f64>::identity(2, 2);
    let mut rows = Rows::new(2);
    rows.push_zeroed(RowKind::Inequality, RowSource::new(LIMIT, 0), -0.5)[0] = -1.0;
    for backend in BACKENDS {
        let (report, qdot, lambda, ws) = solve(&mass, &[3.0, 1.0], &rows, backend)?;
        assert!(report.status.is_solved(), "{backend:?}: {report:?}");
        assert!(
            (qdot[0] - 0.5).abs() < 1e-8 && (qdot[1] - 1.0).abs() < 1e-8,
            "{backend:?}: {qdot:?}"
        );
        assert!((lambda[0] - 2.5).abs() < 1e-7, "{backend:?}: {lambda:?}");
        let impulse = ws.tag_impulse(LIMIT);
        assert!((impulse[0] + 2.5).abs() < 1e-7 && impulse[1] == 0.0);
    }
    Ok(())
}

/// Two conflicting soft thigmotaxis rows, q̇ ≥ 1 and −q̇ ≥ 0 (weight 10 each), with M̃ = 1,
/// f̃ = 0: the exact penalty pays the cheaper slack. Optimum q̇ = 0 (cost ½q̇² + 10·1 is
/// smallest there), slack 1 on the first row, both λ at the weight 10; status solved. (The
/// cost is flat to second order at the optimum, so clarabel's interior point only gets q̇ to
/// ~1e-6 there; the contact-space answer is exact.)
#[test]
fn conflicting_soft_rows_solve_with_reported_slack() -> Result<(), SolverError> {
    let mass = mat![[1.0]];
    let soft = RowKind::SoftInequality { weight: 10.0 };
    let mut rows = Rows::new(1);
    rows.push(soft, RowSource::new(TARGET, 0), 1.0, &[1.0])?;
    rows.push(soft, RowSource::new(TARGET, 0), 0.0, &[-1.0])?;
    for (backend, tolerance) in [(QpBackend::ContactSpace, 1e-12), (QpBackend::Clarabel, 1e-5)] {
        let (report, qdot, lambda, _) = solve(&mass, &[0.0], &rows, backend)?;
        assert!(report.status.is_solved(), "{backend:?}: {report:?}");
        assert!(qdot[0].abs() < tolerance, "{backend:?}: {qdot:?}");
        let at_weight = |l: f64| (l - 10.0).abs() < 10.0 * tolerance;
        assert!(at_weight(lambda[0]) && at_weight(lambda[1]), "{backend:?}: {lambda:?}");
        assert!((report.slack.max - 1.0).abs() < tolerance, "{backend:?}: {report:?}");
        assert!(report.slack.count >= 1, "{backend:?}: {report:?}");
    }
    let (report, _, _, _) = solve(&mass, &[0.0], &rows, QpBackend::ContactSpace)?;
    assert_eq!(report.slack.count, 1);
    assert_eq!(report.status, SolveStatus::Solved);
    Ok(())
}

/// Hard rows q̇ ≥ 1 and −q̇ ≥ 0 contradict each other: status Infeasible, finite numbers.
#[test]
fn infeasible_hard_rows_report_infeasible() -> Result<(), SolverError> {
    let mass = mat![[1.0]];
    let mut rows = Rows::new(1);
    rows.push(RowKind::Inequality, RowSource::new(LIMIT, 0), 1.0, &[1.0])?;
    rows.push(RowKind::Inequality, RowSource::new(WALL, 0), 0.0, &[-1.0])?;
    for backend in BACKENDS {
        let (report, qdot, lambda, _) = solve(&mass, &[0.3], &rows, backend)?;
        assert_eq!(report.status, SolveStatus::Infeasible, "{backend:?}: {report:?}");
        assert!(qdot.iter().chain(&lambda).all(|v| v.is_finite()));
    }
    Ok(())
}

/// A row with c = 0 (a builder emitting an empty Jacobian row) is harmless when b ≤ 0 and
/// infeasible when b > 0 — no division by its zero W entry, no panic.
#[test]
fn zero_rows_are_ignored_or_infeasible() -> Result<(), SolverError> {
    let mass = Mat::<f64>::identity(2, 2);
    for (rhs, expected) in [(-1.0, SolveStatus::Solved), (1.0, SolveStatus::Infeasible)] {
        let mut rows = Rows::new(2);
        rows.push(RowKind::Inequality, RowSource::new(CONTACT, 0), 0.0, &[1.0, 0.0])?;
        rows.push_zeroed(RowKind::Inequality, RowSource::new(CONTACT, 0), rhs);
        for backend in BACKENDS {
            let (report, qdot, lambda, _) = solve(&mass, &[1.0, -1.0], &rows, backend)?;
            assert_eq!(report.status, expected, "{backend:?} b = {rhs}: {report:?}");
            assert!(qdot.iter().chain(&lambda).all(|v| v.is_finite()));
        }
    }
    Ok(())
}

/// Contradicting equalities (q̇₀ = 1 and q̇₀ = 2) on the KKT path are also Infeasible.
#[test]
fn contradicting_equalities_report_infeasible() -> Result<(), SolverError> {
    let mass = Mat::<f64>::identity(2, 2);
    let mut rows = Rows::new(2);
    rows.push(RowKind::Equality, RowSource::new(FIXED, 0), 1.0, &[1.0, 0.0])?;
    rows.push(RowKind::Equality, RowSource::new(FIXED, 0), 2.0, &[1.0, 0.0])?;
    let (report, _, _, _) = solve(&mass, &[0.0, 0.0], &rows, QpBackend::ContactSpace)?;
    assert_eq!((report.path, report.status), (SolvePath::Kkt, SolveStatus::Infeasible));
    Ok(())
}

/// An equality holds the DOF at b = 1 against f̃ = −1 on M̃ = 2: 2·1 = −1 + λ → λ = 3.
#[test]
fn equality_multiplier_follows_the_crate_sign() -> Result<(), SolverError> {
    let mass = mat![[2.0]];
    let mut rows = Rows::new(1);
    rows.push(RowKind::Equality, RowSource::new(FIXED, 0), 1.0, &[1.0])?;
    let (report, qdot, lambda, ws) = solve(&mass, &[-1.0], &rows, QpBackend::ContactSpace)?;
    assert_eq!(
        (report.path, report.status, report.iterations),
        (SolvePath::Kkt, SolveStatus::Solved, 1)
    );
    assert!((qdot[0] - 1.0).abs() < 1e-14 && (lambda[0] - 3.0).abs() < 1e-14);
    assert_eq!(ws.tag_impulse(FIXED), lambda.as_slice());
    Ok(())
}

/// A non-positive-definite M̃ is an error, not a panic.
#[test]
fn indefinite_mass_is_an_error() -> Result<(), SolverError> {
    let mass = mat![[1.0, 2.0], [2.0, 1.0]];
    let rows = Rows::new(2);
    let result = solve(&mass, &[0.0, 0.0], &rows, QpBackend::ContactSpace);
    assert!(matches!(result, Err(SolverError::NotPositiveDefinite { .. })));
    Ok(())
}

/// Six DOFs of unit mass each pushed by 1 against its own wall (row q̇ᵢ ≥ 0.5, f̃ = −1): from
/// λ = 0 every row is violated at once and independent of the others, so one gradient
/// releases all six (the worst, then the rest while independent) and the second iteration
/// finds λᵢ = 1.5 optimal; released one at a time it took seven iterations.
#[test]
fn independent_violated_rows_join_on_one_gradient() -> Result<(), SolverError> {
    let n = 6;
    let mass = Mat::<f64>::identity(n, n);
    let force = vec![-1.0; n];
    let mut rows = Rows::new(n);
    for i in 0..n {
        let mut row = vec![0.0; n];
        row[i] = 1.0;
        rows.push(RowKind::Inequality, RowSource::new(WALL, i), 0.5, &row)?;
    }
    let (report, qdot, lambda, _) = solve(&mass, &force, &rows, QpBackend::ContactSpace)?;
    assert_eq!(report.status, SolveStatus::Solved);
    assert_eq!(report.iterations, 2, "{report:?}");
    for i in 0..n {
        assert!((qdot[i] - 0.5).abs() < 1e-14 && (lambda[i] - 1.5).abs() < 1e-14, "row {i}");
    }
    Ok(())
}
