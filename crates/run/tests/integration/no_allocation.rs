//! A step allocates nothing once warm. Four knotted states are stepped on with their
//! scenario's own controller: the knotted benchmark state (`form.ron` at t = 23.13 s, about
//! 40 self contacts, knot-forming pull; on both dynamics backends, and on the sparse one with
//! friction), `thesis_scripted.ron` at
//! t = 21 s (thigmotaxis rows), `figure_eight.ron` from 12.5 s (the last 0.6 s of the
//! follow-the-leader tie's servos, then its tighten; up to 65 self contacts) and `tie.ron` on
//! ES103 at 1000 bodies (sparse backend) at t = 19 s, a trefoil tied by control. (While a knot
//! is still forming, its growing number of contacts grows the buffers that hold them:
//! `figure_eight.ron` from 11 s allocates 29 times in 200 steps.)
//! After warm-up steps the next steps must not touch the heap (counted by `allocation-counter`
//! on this test's thread, so the tests running alongside do not pollute the count).

use hagfish_bench_support::{knotted_world, long_knotted_world};
use hagfish_control::PhasedController;
use hagfish_scenario::LoadedScenario;
use hagfish_sim::rows::Friction;
use hagfish_sim::{DynamicsBackend, StepOptions, World};

/// Steps after the knotted state before counting (buffers reach their working size).
const WARM_UP_STEPS: usize = 20;
/// Steps counted.
const COUNTED_STEPS: usize = 200;

/// Steps `world` warm, then counts allocations over [`COUNTED_STEPS`] steps; asserts that
/// the stretch is knotted (≥ 20 self contacts at some step) and that nothing was allocated.
fn assert_steps_do_not_allocate(label: &str, world: &mut World, controller: &mut PhasedController) {
    for _ in 0..WARM_UP_STEPS {
        world.step(controller).expect("warm-up step");
    }
    let mut contacts = Vec::with_capacity(COUNTED_STEPS);
    let mut thigmo_rows = 0;
    let change = allocation_counter::measure(|| {
        for _ in 0..COUNTED_STEPS {
            let report = world.step(controller).expect("step");
            contacts.push(report.self_contacts);
            thigmo_rows += world.data().actuation.thigmo.len();
        }
    });
    let most = contacts.iter().copied().max().unwrap_or(0);
    println!("{label}: up to {most} self contacts, {thigmo_rows} thigmotaxis requests");
    assert!(most >= 20, "{label}: not knotted, at most {most} self contacts");
    assert_eq!(
        change.count_total, 0,
        "{label}: {COUNTED_STEPS} knotted steps allocated: {change:?}"
    );
}

#[test]
fn knotted_steps_do_not_allocate() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let (mut world, mut controller) = knotted_world(root.as_ref()).expect("knotted state");
    let sparse_options =
        StepOptions { backend: DynamicsBackend::SparseMaximal, ..world.options().clone() };
    let mut sparse = World::new(world.model().clone(), sparse_options, world.state().clone())
        .expect("sparse world");
    let mut sparse_controller = controller.clone();
    // With friction, each contact's pyramid rows combine three base rows (decision 0029).
    let friction_options =
        StepOptions { friction: Some(Friction::pyramid(0.1, 8)), ..sparse.options().clone() };
    let mut frictional = World::new(world.model().clone(), friction_options, world.state().clone())
        .expect("frictional world");
    let mut frictional_controller = controller.clone();
    assert_steps_do_not_allocate("form.ron", &mut world, &mut controller);
    assert_steps_do_not_allocate("form.ron, sparse backend", &mut sparse, &mut sparse_controller);
    assert_steps_do_not_allocate(
        "form.ron, sparse backend, friction μ = 0.1",
        &mut frictional,
        &mut frictional_controller,
    );
    let thesis =
        LoadedScenario::load(format!("{root}/data/scenarios/thesis_scripted.ron")).expect("loads");
    let (mut world, mut controller) = thesis.build_at(21.0).expect("thesis at 21 s");
    assert_steps_do_not_allocate("thesis_scripted.ron", &mut world, &mut controller);
    // The figure-eight tied by following its template: the joint servos, then the tighten.
    let eight =
        LoadedScenario::load(format!("{root}/data/scenarios/figure_eight.ron")).expect("loads");
    let (mut world, mut controller) = eight.build_at(12.5).expect("figure_eight at 12.5 s");
    assert_steps_do_not_allocate("figure_eight.ron, following", &mut world, &mut controller);

    // ES103 at 1000 bodies (D16: the same animal), the trefoil tied by control.
    let scratch = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    let (mut world, mut controller) =
        long_knotted_world(root.as_ref(), scratch).expect("tie.ron at 1000 bodies, 19 s");
    assert_steps_do_not_allocate("tie.ron, 1000 bodies, sparse", &mut world, &mut controller);
}
