//! Per-stage benchmarks of one step in the knotted benchmark state (`form.ron` at
//! t = 23.13 s, 40 self contacts; see `hagfish_bench_support::knotted_world`), with water drag as the
//! controller (as `benches/step.rs`):
//!
//! kinematics, effective mass M̃ (CRBA) and its Cholesky factor (the dense backend's stages,
//! timed for it; the state's own backend, sparse by default, assembles in `dynamics` and
//! factors in the solve), dynamics (M̃ or the tree factor's blocks, momentum, forces), broad
//! phase, narrow phase, whole contact detection, constraint rows, contact solve
//! (with its velocity-product re-solve), the internal forces (the load each joint transmits),
//! integration, and the whole step.
//!
//! The same detection stages and the contact solve on the long knotted state (1000 bodies,
//! `hagfish_bench_support::long_knotted_world`), group `knotted_1000`.
//!
//! Stages that change their input (solve, integrate, step) are timed with their input reset
//! outside the timed region.

use std::time::{Duration, Instant};

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main};
use hagfish_bench_support::{knotted_world, long_knotted_world};
use hagfish_control::{Controller, WaterDrag};
use hagfish_geometry::ContactDetector;
use hagfish_sim::{StepData, StepOptions, pipeline};
use hagfish_tree::{Model, State};

/// The stages of a step up to its rows (kinematics, detection, control, dynamics, rows): the
/// input of the contact solve, rebuilt untimed before each timed solve.
fn run_to_rows(
    (model, options, state): (&Model, &StepOptions, &State),
    data: &mut StepData,
    controller: &mut dyn Controller,
) {
    pipeline::kinematics(model, state, data);
    pipeline::detect_contacts(model, options, state.t, data).expect("detect");
    pipeline::control(model, options, state, data, controller);
    pipeline::dynamics(model, options, state, data);
    pipeline::build_rows(model, options, state, data);
}

/// Prints the state a group measures: its time, self contacts and rows.
fn print_state(name: &str, state: &State, data: &StepData) {
    let (contacts, rows) = (data.self_contacts.len(), data.rows.len());
    println!("{name} at t = {:.2} s: {contacts} self contacts, {rows} rows", state.t);
}

/// `broad_phase`, `narrow_phase` and `detect_contacts` on the centreline in `data`.
fn bench_detection(
    group: &mut BenchmarkGroup<'_, WallTime>,
    (model, options, state): (&Model, &StepOptions, &State),
    data: &mut StepData,
) {
    let lengths: Vec<f64> = model.bodies().iter().map(|body| body.length).collect();
    let mut detector = ContactDetector::new(options.detector_options(model)).expect("detector");
    let mut contacts = Vec::new();
    group.bench_function("broad_phase", |b| {
        b.iter(|| detector.find_candidates(&data.centreline, &lengths).expect("broad phase"))
    });
    // The narrow phase searches the candidates of the last broad phase: fill them here, so that
    // the benchmark does the real work also when run on its own (`-- narrow_phase`).
    detector.find_candidates(&data.centreline, &lengths).expect("broad phase");
    group.bench_function("narrow_phase", |b| {
        b.iter(|| {
            contacts.clear();
            detector.search_candidates(&data.centreline, &mut contacts)
        })
    });
    group.bench_function("detect_contacts", |b| {
        b.iter(|| pipeline::detect_contacts(model, options, state.t, data).expect("detect"))
    });
}

/// `contact_solve`: the tree factor, both solves, prediction and re-solves, with its input
/// rebuilt by [`run_to_rows`] outside the timed region.
fn bench_contact_solve(
    group: &mut BenchmarkGroup<'_, WallTime>,
    step: (&Model, &StepOptions, &State),
    data: &mut StepData,
    controller: &mut dyn Controller,
) {
    let (model, options, state) = step;
    group.bench_function("contact_solve", |b| {
        b.iter_custom(|iterations| {
            let mut total = Duration::ZERO;
            for _ in 0..iterations {
                run_to_rows(step, data, controller);
                let start = Instant::now();
                pipeline::solve_and_resolve(model, options, state, data, Default::default())
                    .expect("solve");
                total += start.elapsed();
            }
            total
        })
    });
}

fn stages(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let (mut world, _) = knotted_world(root.as_ref()).expect("knotted state");
    let (model, options, state) =
        (world.model().clone(), world.options().clone(), world.state().clone());
    let (model, options) = (&model, &options);
    let h = options.time_step;
    let mut drag = WaterDrag::default();
    let mut data = StepData::new(model, options).expect("step data");
    let step = (model, options, &state);
    run_to_rows(step, &mut data, &mut drag);
    print_state("knotted state", &state, &data);
    let mut group = c.benchmark_group("knotted");
    group.bench_function("kinematics", |b| {
        b.iter(|| pipeline::kinematics(model, &state, &mut data))
    });
    group.bench_function("mass_matrix", |b| {
        b.iter(|| hagfish_tree::effective_mass(model, &mut data.tree, h))
    });
    group.bench_function("factor", |b| {
        b.iter(|| hagfish_tree::factor_effective_mass(&mut data.tree, state.t).expect("SPD"))
    });
    group.bench_function("dynamics", |b| {
        b.iter(|| pipeline::dynamics(model, options, &state, &mut data))
    });
    bench_detection(&mut group, (model, options, &state), &mut data);
    run_to_rows(step, &mut data, &mut drag);
    group.bench_function("rows", |b| {
        b.iter(|| pipeline::build_rows(model, options, &state, &mut data))
    });
    bench_contact_solve(&mut group, step, &mut data, &mut drag);
    run_to_rows(step, &mut data, &mut drag);
    pipeline::solve_and_resolve(model, options, &state, &mut data, Default::default())
        .expect("solve");
    group.bench_function("internal_forces", |b| {
        b.iter(|| pipeline::internal_forces(model, options, &state, &mut data))
    });
    group.bench_function("integrate", |b| {
        b.iter_custom(|iterations| {
            let mut total = Duration::ZERO;
            for _ in 0..iterations {
                let mut next = state.clone();
                let start = Instant::now();
                hagfish_tree::integrate(&mut next, data.solver.velocity(), h).expect("finite");
                total += start.elapsed();
            }
            total
        })
    });
    group.bench_function("step", |b| {
        b.iter_custom(|iterations| {
            let mut total = Duration::ZERO;
            for _ in 0..iterations {
                world.set_state(state.clone()).expect("state");
                let start = Instant::now();
                world.step(&mut drag).expect("step");
                total += start.elapsed();
            }
            total
        })
    });
    group.finish();
}

/// The detection stages and the contact solve on the long knotted state (ES103 at 1000 bodies,
/// `hagfish_bench_support::long_knotted_world`), where each crossing is seen by thousands of
/// segment pairs.
fn long_stages(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let (world, mut controller) =
        long_knotted_world(root.as_ref(), &std::env::temp_dir()).expect("long knotted state");
    let (model, options, state) =
        (world.model().clone(), world.options().clone(), world.state().clone());
    let (model, options) = (&model, &options);
    let mut data = StepData::new(model, options).expect("step data");
    let step = (model, options, &state);
    run_to_rows(step, &mut data, &mut controller);
    print_state("long knotted state", &state, &data);
    let mut group = c.benchmark_group("knotted_1000");
    bench_detection(&mut group, (model, options, &state), &mut data);
    run_to_rows(step, &mut data, &mut controller);
    bench_contact_solve(&mut group, step, &mut data, &mut controller);
    group.finish();
}

criterion_group!(benches, stages, long_stages);
criterion_main!(benches);
