//! Whole-step benchmarks of the 100-body ES103 hagfish (`data/hagfish/es103.ron`).
//!
//! - `step/unconstrained`: one linearly implicit Euler step of the free chain (kinematics,
//!   CRBA of M̃, momentum, Newton–Euler forces, Cholesky, solve, integrate) in a bent, moving
//!   state.
//! - `step/knotted/<backend>`: one whole pipeline step (kinematics, contact detection,
//!   drag, dynamics, rows, constraint solve with its re-solves, integration) in the knotted
//!   benchmark state (`hagfish_bench_support::knotted_world`: `data/scenarios/form.ron` at t = 23.13 s,
//!   40 self contacts), with the contact-space QP on the sparse maximal-coordinate backend
//!   (both the defaults) and with clarabel on the dense backend (reference);
//!   `step/knotted/ContactSpace/DenseReduced`, the same step on the dense reduced backend
//!   (`StepOptions::backend`); and `step/knotted/ContactSpace/NoPrediction`, the default
//!   without contact prediction (its cost); `step/knotted/ContactSpace/Skin`, the default on
//!   the same body with a skin (φ 0.25, p 1000 dyn/cm²: a core and a skin row per contact).
//!   Each iteration restores the state first (`World::set_state`, untimed).
//! - `step/knotted_1000/SparseMaximal`: the same whole step in a long chain: ES103 at 1000
//!   bodies on the sparse backend, `data/scenarios/tie.ron` at t = 19 s (a trefoil tied by
//!   control, `hagfish_bench_support::long_knotted_world`), with the scenario's controller.
//!   Per-stage benchmarks of the same state: `cargo bench -p hagfish-sim --bench stages`.
//! - `step/overhand_9_1/SparseMaximal`: one whole step of Choi et al.'s 9₁ as published
//!   (`data/validation/overhand_pull.ron` started from `data/knots/imc-der/n4.txt`: 600 bodies,
//!   μ = 0.1 on the friction pyramid of decisions 0029–0030), held 0.5 s first: ≈ 480 self
//!   contacts of 8 rows each, the solver's largest case (`cargo bench --bench step --
//!   overhand_9_1`).
//! - `step/thigmo_space/<space>`: one whole step in the knotted benchmark state under the
//!   slide's thigmotaxis (2 cm/s at both contacts, four rows), with the rows confined to
//!   `Full` (no projection) and to a modal space of k = 4 (`c̃ = B(Bᵀc)`, B four orthonormal
//!   sines along the body): the cost of the projection, side by side.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use hagfish_bench_support::{knotted_world, long_knotted_world};
use hagfish_control::{
    ControllerState, ForceSpace, KindSelection, ModalBasis, ModalSpace, Phase, PhasedController,
    SlidingTargets, ThigmoParameters, ThigmoPhase, Until, WaterDrag,
};
use hagfish_scenario::{LoadedScenario, Override};
use hagfish_sim::rows::RowGroup;
use hagfish_sim::{DynamicsBackend, StepOptions, World, dof_labels, rest_dof_arc_lengths};
use hagfish_solver::{QpBackend, SolverOptions};
use hagfish_tree::{Data, State, step_unconstrained};

fn form_scenario() -> LoadedScenario {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/scenarios/form.ron");
    LoadedScenario::load(path).expect("form.ron loads")
}

fn unconstrained(c: &mut Criterion) {
    let model = form_scenario().body.to_model().expect("model");
    let mut state = State::rest(&model);
    for a in 0..model.dof_count() {
        state.q[a] = 0.2 * (a as f64 * 0.37).sin();
        state.qdot[a] = 0.2 * (a as f64 * 0.91).cos();
    }
    let mut data = Data::new(&model);
    c.bench_function("step/unconstrained", |b| {
        b.iter_batched_ref(
            || state.clone(),
            |s| step_unconstrained(&model, s, 0.01, &mut data).expect("step"),
            BatchSize::SmallInput,
        )
    });
}

fn knotted(c: &mut Criterion) {
    let (world, _) = knotted_world(env!("CARGO_MANIFEST_DIR").as_ref()).expect("knotted state");
    let knotted = world.state().clone();
    let prediction = StepOptions::default().contact_prediction;
    for (backend, dynamics, contact_prediction, name) in [
        (QpBackend::ContactSpace, DynamicsBackend::SparseMaximal, prediction, "ContactSpace"),
        (QpBackend::Clarabel, DynamicsBackend::DenseReduced, prediction, "Clarabel"),
        (
            QpBackend::ContactSpace,
            DynamicsBackend::DenseReduced,
            prediction,
            "ContactSpace/DenseReduced",
        ),
        (
            QpBackend::ContactSpace,
            DynamicsBackend::SparseMaximal,
            None,
            "ContactSpace/NoPrediction",
        ),
    ] {
        let model = world.model().clone();
        let options = StepOptions {
            solver: SolverOptions { backend, ..SolverOptions::default() },
            backend: dynamics,
            contact_prediction,
            ..StepOptions::default()
        };
        bench_knotted_step(c, name, World::new(model, options, knotted.clone()).expect("world"));
    }
    // The same body with a skin (docs/physics.md, "Skin"): a core row and a compliant skin row
    // per contact.
    let Ok(hagfish_anatomy::Body::Hagfish(mut biometrics)) =
        hagfish_anatomy::Body::load(&form_scenario().scenario.body)
    else {
        panic!("form.ron's body is a hagfish");
    };
    biometrics.skin =
        Some(hagfish_anatomy::BodySkin { thickness_fraction: 0.25, pressure_dyn_per_cm2: 1000.0 });
    let skinned = biometrics.to_model().expect("the skinned model");
    let options = StepOptions::default();
    bench_knotted_step(
        c,
        "ContactSpace/Skin",
        World::new(skinned, options, knotted).expect("world"),
    );
}

/// Benchmarks one step of `world` from its current (knotted) state as `step/knotted/{name}`,
/// under water drag; each iteration restores the state first (untimed: `set_state` runs the
/// kinematics once more).
fn bench_knotted_step(c: &mut Criterion, name: &str, mut world: World) {
    let knotted = world.state().clone();
    let mut drag = WaterDrag::default();
    world.step(&mut drag).expect("warm-up step");
    println!(
        "knotted state ({name}): {} self contacts, rows per group {:?}",
        world.data().report.self_contacts,
        RowGroup::values(&world.data().report.solve.rows_per_tag)
    );
    c.bench_function(&format!("step/knotted/{name}"), |b| {
        b.iter_custom(|iterations| {
            let mut elapsed = Duration::ZERO;
            for _ in 0..iterations {
                world.set_state(knotted.clone()).expect("state");
                let start = Instant::now();
                black_box(world.step(&mut drag).expect("step").solve.iterations);
                elapsed += start.elapsed();
            }
            elapsed
        })
    });
}

fn long_knotted(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let (world, controller) =
        long_knotted_world(root.as_ref(), &std::env::temp_dir()).expect("long knotted state");
    let label = format!("long knotted state, {} bodies", world.model().body_count());
    bench_steps(c, ("knotted_1000/SparseMaximal", &label, 20), world, controller);
}

/// Choi et al.'s 9₁ held 0.5 s from its published shape, then one step timed at a time.
fn overhand_9_1(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/validation/overhand_pull.ron");
    let shape =
        r#"initial_shape=Some(Polyline((file: "../knots/imc-der/n4.txt", cm_per_unit: 100.0)))"#;
    let overrides = [Override::parse(shape).expect("an override")];
    let loaded = LoadedScenario::load_with(path, &overrides).expect("overhand_pull.ron loads");
    let (mut world, mut controller) = loaded.build().expect("the 9₁ at rest");
    while world.state().t < 0.5 {
        world.step(&mut controller).expect("held");
    }
    bench_steps(c, ("overhand_9_1/SparseMaximal", "the 9₁ held 0.5 s", 10), world, controller);
}

/// Benchmarks one step of `world` under `controller` from their current states as
/// `step/{id}` with `samples` samples, after a warm-up step that prints the contacts and rows
/// under `label`.
fn bench_steps(
    c: &mut Criterion,
    (id, label, samples): (&str, &str, usize),
    mut world: World,
    mut controller: PhasedController,
) {
    let (start, saved) = (world.state().clone(), controller.state());
    world.step(&mut controller).expect("warm-up step");
    println!(
        "{label}: {} self contacts, rows per group {:?}",
        world.data().report.self_contacts,
        RowGroup::values(&world.data().report.solve.rows_per_tag)
    );
    let mut group = c.benchmark_group("step");
    group.sample_size(samples);
    group.bench_function(id, |b| time_steps_from(b, &mut world, &mut controller, &start, &saved));
    group.finish();
}

/// The knotted state's step under the slide's thigmotaxis, `Full` against `Modes` k = 4.
fn thigmo_space(c: &mut Criterion) {
    let (mut world, _) = knotted_world(env!("CARGO_MANIFEST_DIR").as_ref()).expect("knotted");
    let knotted = world.state().clone();
    let model = world.model().clone();
    let length = form_scenario().body.length_cm();
    let (arcs, labels) = (rest_dof_arc_lengths(&model), dof_labels(&model));
    let sines: Vec<Vec<f64>> = (1..=4)
        .map(|j| {
            let shift = |axis: char| f64::from(u32::from(axis) - u32::from('X'));
            let wave = |s: f64, a: char| j as f64 * std::f64::consts::PI * s / length + shift(a);
            arcs.iter().zip(&labels).map(|(s, l)| wave(*s, l.axis).sin()).collect()
        })
        .collect();
    let basis = ModalBasis::orthonormal(model.dof_count(), &sines).expect("four sines");
    let modal = ModalSpace {
        file: "sines".into(),
        kind: KindSelection::All,
        modes: 4,
        basis: Some(std::sync::Arc::new(basis)),
    };
    let mut group = c.benchmark_group("step/thigmo_space");
    for (name, force_space) in [("Full", ForceSpace::Full), ("Modes4", ForceSpace::Modes(modal))] {
        let targets = SlidingTargets { v_a: 2.0, v_b: 2.0 };
        let parameters = ThigmoParameters {
            head: targets,
            tail: targets,
            tail_pull_dyn: 20.0,
            max_force_dyn: 2000.0,
            force_space,
            replay: None,
        };
        let phase = ThigmoPhase {
            name: "slide".into(),
            parameters,
            until: Until { seconds: 1e3, ..Until::default() },
        };
        let mut controller =
            PhasedController::new(Some(WaterDrag::default()), vec![Phase::Thigmotaxis(phase)]);
        world.set_state(knotted.clone()).expect("state");
        world.step(&mut controller).expect("warm-up step");
        let saved = controller.state();
        group.bench_function(name, |b| {
            time_steps_from(b, &mut world, &mut controller, &knotted, &saved)
        });
    }
    group.finish();
}

/// Times single steps of `world` from `start`, `controller` restored to `saved` before
/// each (the restoring is not timed).
fn time_steps_from(
    b: &mut criterion::Bencher<'_>,
    world: &mut World,
    controller: &mut PhasedController,
    start: &State,
    saved: &ControllerState,
) {
    b.iter_custom(|iterations| {
        let mut elapsed = Duration::ZERO;
        for _ in 0..iterations {
            world.set_state(start.clone()).expect("state");
            controller.restore(saved).expect("controller state");
            let begin = Instant::now();
            black_box(world.step(controller).expect("step").solve.iterations);
            elapsed += begin.elapsed();
        }
        elapsed
    })
}

criterion_group!(benches, unconstrained, knotted, long_knotted, overhand_9_1, thigmo_space);
criterion_main!(benches);
