//! The solver used as a third party would: its own row kinds, no hagfish type.
//!
//! A point mass in the plane (q̇ = (vx, vy), M̃ = m·I) falls onto a floor while a rope from
//! the origin keeps it from moving sideways. The caller defines two row kinds, `FLOOR` and
//! `ROPE`, and ids of its own (which floor, which rope); the report counts rows and active
//! rows per kind, the workspace sums impulses per kind, and each multiplier is traced back to
//! its source by its id, not by its position. A [`Factored`] handle then solves the same rows
//! with a new force and new bounds, and refuses inputs of the wrong size.

use faer::Mat;
use hagfish_solver::{
    Factored, Mass, RowKind, RowSource, RowTag, Rows, SolveStatus, SolverError, SolverWorkspace,
};

/// The caller's row kinds: ids it chooses, meanings only it knows.
const FLOOR: RowTag = RowTag::new(7);
const ROPE: RowTag = RowTag::new(11);

/// The floor this program calls number 42 and the rope it calls number 3.
const FLOOR_ID: usize = 42;
const ROPE_ID: usize = 3;

const MASS_G: f64 = 2.0;

/// Rows: the floor stops downward motion (vy ≥ 0), the rope holds x still (vx = 0).
fn rows() -> Result<Rows, SolverError> {
    let mut rows = Rows::new(2);
    rows.push(RowKind::Equality, RowSource::new(ROPE, ROPE_ID), 0.0, &[1.0, 0.0])?;
    rows.push(RowKind::Inequality, RowSource::new(FLOOR, FLOOR_ID), 0.0, &[0.0, 1.0])?;
    Ok(rows)
}

/// The multiplier of the row that `source` produced, found by provenance.
fn multiplier_of(rows: &Rows, lambda: &[f64], source: RowSource) -> Option<f64> {
    rows.sources().iter().position(|s| *s == source).map(|row| lambda[row])
}

#[test]
fn a_caller_defined_row_kind_is_reported_and_traced_by_its_own_tags() -> Result<(), SolverError> {
    let mass = Mat::<f64>::identity(2, 2) * MASS_G;
    let rows = rows()?;
    // Momentum m·v⁰ with v⁰ = (1, −3): moving sideways and down.
    let force = [MASS_G, -3.0 * MASS_G];
    let mut workspace = SolverWorkspace::default();
    let mut factored: Factored<'_> = workspace.factor(Mass::Dense(mass.as_ref()), &rows)?;
    let report = *factored.solve(&force, rows.rhs())?;
    assert_eq!(report.status, SolveStatus::Solved);
    assert_eq!((report.rows_per_tag[FLOOR], report.rows_per_tag[ROPE]), (1, 1));
    assert_eq!((report.active_per_tag[FLOOR], report.active_per_tag[ROPE]), (1, 1));
    let other_kinds: usize = report
        .rows_per_tag
        .iter()
        .filter(|(tag, _)| ![FLOOR, ROPE].contains(tag))
        .map(|(_, n)| n)
        .sum();
    assert_eq!(other_kinds, 0);

    let solver = factored.workspace();
    assert!(solver.velocity().iter().all(|v| v.abs() < 1e-12), "{:?}", solver.velocity());
    // Impulses stop the motion: the floor pushes up by 3m, the rope pulls back by m.
    let floor = multiplier_of(&rows, solver.multipliers(), RowSource::new(FLOOR, FLOOR_ID));
    let rope = multiplier_of(&rows, solver.multipliers(), RowSource::new(ROPE, ROPE_ID));
    assert!((floor.unwrap_or(f64::NAN) - 3.0 * MASS_G).abs() < 1e-12);
    assert!((rope.unwrap_or(f64::NAN) + MASS_G).abs() < 1e-12);
    assert!((solver.tag_impulse(FLOOR)[1] - 3.0 * MASS_G).abs() < 1e-12);
    assert_eq!(solver.tag_impulse(FLOOR)[0], 0.0);
    assert!((solver.tag_impulse(ROPE)[0] + MASS_G).abs() < 1e-12);
    assert!(solver.tag_impulse(RowTag::new(0)).iter().all(|v| *v == 0.0));
    Ok(())
}

/// A kind of row present in one solve and gone in the next leaves no impulse behind.
#[test]
fn a_kind_without_rows_has_no_impulse_after_one_that_had() -> Result<(), SolverError> {
    let mass = Mat::<f64>::identity(2, 2) * MASS_G;
    let mut workspace = SolverWorkspace::default();
    let both = rows()?;
    workspace
        .factor(Mass::Dense(mass.as_ref()), &both)?
        .solve(&[MASS_G, -3.0 * MASS_G], both.rhs())?;
    assert!(workspace.tag_impulse(FLOOR)[1] > 0.0);
    let mut rope_only = Rows::new(2);
    rope_only.push(RowKind::Equality, RowSource::new(ROPE, ROPE_ID), 0.0, &[1.0, 0.0])?;
    let force = [MASS_G, -3.0 * MASS_G];
    workspace.factor(Mass::Dense(mass.as_ref()), &rope_only)?.solve(&force, rope_only.rhs())?;
    assert_eq!(workspace.tag_impulse(FLOOR), &[0.0, 0.0], "the floor had rows before");
    assert!((workspace.tag_impulse(ROPE)[0] + MASS_G).abs() < 1e-12);
    Ok(())
}

#[test]
fn a_factored_problem_is_solved_again_with_new_bounds_and_refuses_wrong_sizes()
-> Result<(), SolverError> {
    let mass = Mat::<f64>::identity(2, 2) * MASS_G;
    let rows = rows()?;
    let mut workspace = SolverWorkspace::default();
    let mut factored = workspace.factor(Mass::Dense(mass.as_ref()), &rows)?;
    factored.solve(&[MASS_G, -3.0 * MASS_G], rows.rhs())?;
    // The floor now asks to lift off at 0.5 cm/s and the rope to reel in at 0.25 cm/s.
    let report = *factored.solve(&[0.0, -MASS_G], &[-0.25, 0.5])?;
    assert_eq!(report.status, SolveStatus::Solved);
    assert!(report.warm_started);
    let velocity = factored.workspace().velocity();
    assert!((velocity[0] + 0.25).abs() < 1e-12 && (velocity[1] - 0.5).abs() < 1e-12);

    let short_rhs = factored.solve(&[0.0, 0.0], &[0.0]);
    assert!(matches!(short_rhs, Err(SolverError::DimensionMismatch { expected: 2, found: 1, .. })));
    let long_force = factored.solve(&[0.0; 3], rows.rhs());
    assert!(matches!(
        long_force,
        Err(SolverError::DimensionMismatch { expected: 2, found: 3, .. })
    ));
    let nan = factored.solve(&[0.0, 0.0], &[f64::NAN, 0.0]);
    assert!(matches!(nan, Err(SolverError::NonFinite { what: "row rhs", row: 0, .. })));
    Ok(())
}

#[test]
fn an_asymmetric_mass_is_refused_when_factored() -> Result<(), SolverError> {
    let mut mass = Mat::<f64>::identity(2, 2);
    mass[(0, 1)] = 0.5;
    let rows = rows()?;
    let mut workspace = SolverWorkspace::default();
    let refused = workspace.factor(Mass::Dense(mass.as_ref()), &rows);
    assert!(matches!(refused, Err(SolverError::NotSymmetric { row: 0, col: 1, .. })));
    Ok(())
}

#[test]
fn a_failed_first_solve_leaves_no_factor_to_reuse() -> Result<(), SolverError> {
    let rows = rows()?;
    let mut workspace = SolverWorkspace::default();
    let spd = Mat::<f64>::identity(2, 2);
    workspace.factor(Mass::Dense(spd.as_ref()), &rows)?.solve(&[1.0, -1.0], rows.rhs())?;
    // Same sizes, but M̃ is indefinite: every solve of its handle must fail, none may reuse the
    // factor of the previous M̃ (a failed factorisation marks the workspace's factor invalid).
    let indefinite = Mat::<f64>::identity(2, 2) * -1.0;
    let mut factored = workspace.factor(Mass::Dense(indefinite.as_ref()), &rows)?;
    for attempt in 0..2 {
        let outcome = factored.solve(&[1.0, -1.0], rows.rhs());
        assert!(
            matches!(outcome, Err(SolverError::NotPositiveDefinite { .. })),
            "attempt {attempt}"
        );
    }
    Ok(())
}
