//! The sparse maximal-coordinate backend in the whole pipeline: from the same state it gives
//! the dense reduced path's `q̇¹` (to 1e-9 relative) and multipliers (to 1e-9 or 10·cond(M̃)·ε) on the 100-body ES103
//! hagfish — with the head rows only, with joint-limit, wall and self-contact rows while a
//! force drags the tail around, and in the knotted benchmark state (`form.ron` at 23.13 s) with
//! its self contacts and re-solves —
//! the whole `form.ron` run on it ties the same trefoil, and a 1000-body chain steps stably
//! on it.

use crate::common::SweepingTailForce;
use hagfish_control::{Controller, WaterDrag};
use hagfish_scenario::LoadedScenario;
use hagfish_sim::rows::RowGroup;
use hagfish_sim::{DynamicsBackend, StepOptions, World};
use hagfish_solver::SolvePath;
use hagfish_tree::{Model, State};

fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    let diff: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt();
    let norm: f64 = b.iter().map(|y| y * y).sum::<f64>().sqrt();
    diff / norm.max(1e-300)
}

fn with_backend(options: &StepOptions, backend: DynamicsBackend) -> StepOptions {
    StepOptions { backend, ..options.clone() }
}

/// The 2-norm condition number of the symmetric positive definite `matrix`.
fn condition(matrix: faer::MatRef<'_, f64>) -> f64 {
    let eigenvalues = matrix.self_adjoint_eigenvalues(faer::Side::Lower).expect("symmetric");
    eigenvalues[eigenvalues.len() - 1] / eigenvalues[0]
}

/// One step from `state` on each backend (fresh worlds, so neither is warm-started). Checks
/// that q̇¹ (and λ, when both steps have the same rows, to the conditioning bound below) agree to
/// `tolerance` (relative) and that
/// the sparse answer satisfies `M̃q̇ = f̃ + Cᵀλ` with the dense M̃ to rounding; returns the
/// dense step's solve path and rows per group.
fn compare_one_step(
    model: &Model,
    options: &StepOptions,
    state: &State,
    tolerance: f64,
    controller: &mut dyn FnMut() -> Box<dyn Controller>,
) -> (SolvePath, [usize; RowGroup::COUNT]) {
    let mut worlds = Vec::new();
    for backend in [DynamicsBackend::DenseReduced, DynamicsBackend::SparseMaximal] {
        let mut world = World::new(model.clone(), with_backend(options, backend), state.clone())
            .expect("world");
        world.step(controller().as_mut()).expect("step succeeds");
        worlds.push(world);
    }
    let (dense, sparse) = (worlds[0].data(), worlds[1].data());
    let (path, rows) =
        (dense.report.solve.path, RowGroup::values(&dense.report.solve.rows_per_tag));
    assert_eq!(path, sparse.report.solve.path, "same solve path");
    let (qdot, lambda) = (&worlds[1].state().qdot, sparse.solver.multipliers());
    let velocity_error = relative_error(qdot, &worlds[0].state().qdot);
    assert!(velocity_error < tolerance, "q̇¹ differs by {velocity_error:e} (relative)");
    let sparse_rows = RowGroup::values(&sparse.report.solve.rows_per_tag);
    if rows == sparse_rows {
        if !lambda.is_empty() {
            // λ is as sensitive to rounding as W = C M̃⁻¹Cᵀ is ill-conditioned, and cond(W) ≤
            // cond(M̃), which reaches 10⁸ for this chain: the bound is `tolerance` or
            // 10·cond(M̃)·ε, whichever is larger (as for the round trip in hagfish-tree).
            let bound =
                tolerance.max(10.0 * condition(dense.tree.effective_mass.as_ref()) * f64::EPSILON);
            let multiplier_error = relative_error(lambda, dense.solver.multipliers());
            assert!(
                multiplier_error < bound,
                "λ differs by {multiplier_error:e} (relative, bound {bound:e})"
            );
        }
    } else {
        // A joint whose first-solve velocity lands on its limit to rounding gets an
        // overshoot row on one backend only; such a row is inactive (q̇¹ agrees above).
        for group in [RowGroup::Head, RowGroup::Wall, RowGroup::Contact, RowGroup::Thigmo] {
            assert_eq!(rows[group as usize], sparse_rows[group as usize], "{group:?} rows");
        }
    }
    // Backward error of the sparse answer in the dense system: the dense M̃; f̃, rows and λ of
    // the sparse step (its velocity-product refresh used its own first q̇).
    let (mass, force) = (&dense.tree.effective_mass, &sparse.tree.effective_momentum);
    let (mut worst, mut scale) = (0.0f64, 1.0f64);
    let coefficients: Vec<Vec<f64>> =
        (0..lambda.len()).filter_map(|i| sparse.rows.row(i)).map(|r| r.to_vec()).collect();
    for (a, f) in force.iter().enumerate() {
        let product: f64 = (0..qdot.len()).map(|b| mass[(a, b)] * qdot[b]).sum();
        let impulse: f64 = lambda.iter().zip(&coefficients).map(|(l, c)| l * c[a]).sum();
        worst = worst.max((product - f - impulse).abs());
        scale = scale.max(product.abs()).max(f.abs()).max(impulse.abs());
    }
    assert!(worst / scale < 1e-12, "sparse answer's dense stationarity {:e}", worst / scale);
    (path, rows)
}

fn form_scenario() -> LoadedScenario {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/form.ron");
    LoadedScenario::load(path).expect("form.ron loads")
}

#[test]
fn sparse_steps_like_dense_with_head_limit_wall_and_contact_rows() {
    let model = form_scenario().body.to_model().expect("ES103 builds");
    let options = StepOptions::default();
    let mut state = State::rest(&model);
    for a in 0..model.dof_count() {
        state.q[a] = 0.05 * (a as f64 * 0.37).sin();
        state.qdot[a] = 0.2 * (a as f64 * 0.91).cos();
    }
    let mut make = || -> Box<dyn Controller> { Box::new(SweepingTailForce(20.0)) };
    let (path, rows) = compare_one_step(&model, &options, &state, 1e-9, &mut make);
    assert_eq!(path, SolvePath::Kkt, "a free bent chain has only the head rows");
    assert!(rows[RowGroup::Head as usize] > 0);

    // Drive the dense world for 10 s and compare a step from every 50th state.
    let mut world = World::new(model.clone(), options.clone(), state).expect("world");
    let mut force = SweepingTailForce(20.0);
    let (mut limit_steps, mut wall_steps, mut contact_steps) = (0, 0, 0);
    for step in 1..=1000 {
        world.step(&mut force).expect("dense step");
        if step % 50 == 0 {
            let (_, rows) = compare_one_step(&model, &options, world.state(), 1e-9, &mut make);
            limit_steps += usize::from(rows[RowGroup::Limit as usize] > 0);
            wall_steps += usize::from(rows[RowGroup::Wall as usize] > 0);
            contact_steps += usize::from(rows[RowGroup::Contact as usize] > 0);
        }
    }
    assert!(limit_steps > 0, "some compared step has limit rows");
    assert!(wall_steps > 0, "some compared step has wall rows");
    assert!(contact_steps > 0, "some compared step has self-contact rows");
}

#[test]
fn sparse_steps_like_dense_in_the_knotted_state() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let (world, _) = hagfish_bench_support::knotted_world(root.as_ref()).expect("knotted state");
    let model = world.model().clone();
    let options = world.options().clone();
    let mut make = || -> Box<dyn Controller> { Box::new(WaterDrag::default()) };
    let (path, rows) = compare_one_step(&model, &options, world.state(), 1e-9, &mut make);
    println!("knotted benchmark state: rows per group {rows:?}");
    assert_eq!(path, SolvePath::Qp);
    assert!(rows[RowGroup::Contact as usize] > 20, "knotted: self contacts, got {rows:?}");
}

/// The rows of the knotted state keep the promise of their breaks (`hagfish_solver::WrenchBreaks`):
/// between two breaks (and below the first) a row's coefficients are one wrench's generalized
/// force, cₐ = sₐᵀF, within 10⁻¹² of the row's largest coefficient (its residual from the span
/// of the range's axes [ω_a, v_a], by a thin QR); every contact, limit and head row promises
/// breaks (the 41 rows are too few for the solve to compress: `hagfish-sparse`'s
/// `compressed_spans` tests that).
#[test]
fn the_knotted_state_s_rows_are_one_wrench_between_their_breaks() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let (mut world, _) =
        hagfish_bench_support::knotted_world(root.as_ref()).expect("knotted state");
    let start = world.state().clone();
    world.step(&mut WaterDrag::default()).expect("step succeeds");
    let (data, model) = (world.data(), world.model());
    // The axes of the state the rows were built at (the step's end has moved them).
    let mut kinematics = hagfish_tree::Data::new(model);
    hagfish_tree::forward_kinematics(model, &start.q, &start.qdot, &mut kinematics);
    let rows = &data.rows;
    let mut ranges_checked = 0;
    for i in 0..rows.len() {
        let breaks = rows
            .breaks(i)
            .unwrap_or_else(|| panic!("row {i} ({:?}) promises no breaks", rows.sources()[i]));
        let c = rows.row(i).expect("a row").to_vec();
        let largest = c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let support = c.iter().rposition(|&x| x != 0.0).map_or(0, |e| e + 1);
        let mut ends: Vec<usize> =
            breaks.positions().iter().copied().filter(|&b| b < support).collect();
        ends.extend([0, support]);
        ends.sort_unstable();
        ends.dedup();
        for range in ends.windows(2).map(|w| w[0]..w[1]).filter(|r| r.len() > 6) {
            let axes = faer::Mat::<f64>::from_fn(range.len(), 6, |k, j| {
                let s = &kinematics.axes[range.start + k];
                [s.angular.x, s.angular.y, s.angular.z, s.linear.x, s.linear.y, s.linear.z][j]
            });
            let q = axes.qr().compute_thin_Q();
            let segment = faer::Mat::<f64>::from_fn(range.len(), 1, |k, _| c[range.start + k]);
            let residual = &segment - &q * (q.transpose() * &segment);
            let worst = residual.col(0).iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            assert!(worst <= 1e-12 * largest, "row {i}, DOFs {range:?}: {worst:e} off one wrench");
            ranges_checked += 1;
        }
    }
    assert!(ranges_checked > 20, "{ranges_checked} ranges checked ({} DOFs)", model.dof_count());
}

#[test]
fn the_sparse_backend_ties_the_trefoil_of_form_ron() {
    let loaded = form_scenario();
    let (dense_world, mut controller) = loaded.build().expect("world");
    let options = with_backend(dense_world.options(), DynamicsBackend::SparseMaximal);
    let state = dense_world.state().clone();
    let mut world = World::new(dense_world.model().clone(), options, state).expect("world");
    let steps = (loaded.scenario.duration_s / loaded.scenario.time_step_s).round() as usize;
    let mut max_penetration = 0.0f64;
    for _ in 0..steps {
        let report = *world.step(&mut controller).expect("sparse step");
        max_penetration = max_penetration.max(report.max_self_penetration_relative);
    }
    let mut centres = Vec::new();
    world.body_centres(&mut centres);
    let knot = hagfish_knots::analyse_knot(&centres, &hagfish_knots::KnotOptions::default())
        .expect("knot analysis");
    println!(
        "sparse form.ron: {:?} (agreement {}), max self penetration {:.2} % of r",
        knot.knot,
        knot.agreement,
        100.0 * max_penetration
    );
    assert_eq!(knot.knot, hagfish_knots::KnotType::Trefoil, "{knot:?}");
    assert!(knot.agreement >= 0.9, "agreement {}", knot.agreement);
    assert!(max_penetration < 0.05, "max self penetration {max_penetration} of the radius");
}

#[test]
fn a_thousand_body_chain_steps_stably_on_the_sparse_backend() {
    let model = hagfish_anatomy::segment_chain(1000).expect("chain");
    let options = StepOptions {
        backend: DynamicsBackend::SparseMaximal,
        wall: None,
        ..StepOptions::default()
    };
    let mut state = State::rest(&model);
    for a in 0..model.dof_count() {
        state.q[a] = 0.02 * (a as f64 * 0.37).sin();
        state.qdot[a] = 0.5 * (a as f64 * 0.91).cos();
    }
    let mut world = World::new(model.clone(), options.clone(), state).expect("world");
    let mut drag = WaterDrag::default();
    let (mut head_rows, mut fastest) = (0, 0.0f64);
    for _ in 0..200 {
        let report = *world.step(&mut drag).expect("sparse step");
        assert!(report.solve.status.is_solved());
        head_rows = head_rows.max(report.solve.rows_per_tag[RowGroup::Head.tag()]);
        let state = world.state();
        assert!(state.q.iter().chain(&state.qdot).all(|v| v.is_finite()));
        fastest = fastest.max(state.qdot.iter().fold(0.0f64, |m, v| m.max(v.abs())));
    }
    // Started at |q̇| ≤ 0.5 rad/s with the springs stretched: bounded, no blow-up.
    assert!(fastest < 5.0, "max |q̇| over 200 steps = {fastest}");
    assert!(head_rows > 0);
    // The head joint is held at rest by its rows.
    assert!(world.state().q[0].abs() < 1e-9, "head twist {}", world.state().q[0]);
    // And the step still solves the dense step's system to rounding at 1000 bodies. M̃ of
    // the 1000-body chain is so ill-conditioned that two backward-stable answers differ by
    // ~1e-7 (measured 8e-8; residuals: dense 2.6e-14, sparse 9e-16 relative).
    let mut make = || -> Box<dyn Controller> { Box::new(WaterDrag::default()) };
    compare_one_step(&model, &options, world.state(), 1e-6, &mut make);
}
