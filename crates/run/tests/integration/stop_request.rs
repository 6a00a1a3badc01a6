//! A stop asked for during a step (a SIGTERM's flag, [`StopRequest`]) abandons the step at a
//! stage boundary and leaves no trace: the state, the step count and the controller are the
//! step's start, and the run continues from there bit for bit as if it had never been asked
//! (issue 39, item 6: a step of a huge body takes tens of seconds, a stop must not wait for it).

use std::sync::atomic::{AtomicBool, Ordering};

use hagfish_run::{FrameSink, RunEnd, RunOptions};
use hagfish_scenario::LoadedScenario;
use hagfish_sim::{StepOutcome, StepTally, StopRequest, World};

/// `form.ron` built and stepped to 1 s (contacts and the forming script under way).
fn forming_at_one_second() -> (World, hagfish_control::PhasedController) {
    let path = format!("{}/../../data/scenarios/form.ron", env!("CARGO_MANIFEST_DIR"));
    let loaded = LoadedScenario::load(&path).expect("form.ron loads");
    loaded.build_at(1.0).expect("form.ron builds and steps")
}

/// The bits of t, q and q̇.
fn bits(world: &World) -> Vec<u64> {
    let state = world.state();
    let values = std::iter::once(&state.t).chain(&state.q).chain(&state.qdot);
    values.map(|x| x.to_bits()).collect()
}

#[test]
fn a_stopped_step_leaves_the_state_and_the_controller_at_its_start() {
    let (mut world, mut controller) = forming_at_one_second();
    let (mut reference, mut reference_controller) = forming_at_one_second();
    let (start, steps, phase) = (bits(&world), world.steps(), controller.state());
    let mut tally = StepTally::default();
    let stop = AtomicBool::new(true);
    let outcome = world.advance(&mut controller, &mut tally, StopRequest::new(Some(&stop)));
    assert!(matches!(outcome, StepOutcome::Stopped), "{outcome:?}");
    assert!(bits(&world) == start, "the state moved");
    assert_eq!(world.steps(), steps);
    assert_eq!(controller.state(), phase);
    // Continued without the stop, it takes the steps the reference takes, bit for bit.
    stop.store(false, Ordering::Relaxed);
    for _ in 0..5 {
        let stop = StopRequest::new(Some(&stop));
        let outcome = world.advance(&mut controller, &mut tally, stop);
        assert!(matches!(outcome, StepOutcome::Accepted), "{outcome:?}");
        let outcome =
            reference.advance(&mut reference_controller, &mut tally, StopRequest::default());
        assert!(matches!(outcome, StepOutcome::Accepted), "{outcome:?}");
        assert!(bits(&world) == bits(&reference), "step {} differs", world.steps());
    }
}

#[test]
fn a_stop_set_by_another_thread_mid_step_is_taken_or_leaves_no_trace() {
    let (mut reference, mut reference_controller) = forming_at_one_second();
    let mut tally = StepTally::default();
    let _ = reference.advance(&mut reference_controller, &mut tally, StopRequest::default());
    let after_one_step = bits(&reference);
    for delay_us in [0, 20, 50, 100, 200, 400, 800, 1600] {
        let (mut world, mut controller) = forming_at_one_second();
        let start = bits(&world);
        let flag = AtomicBool::new(false);
        let outcome = std::thread::scope(|scope| {
            scope.spawn(|| {
                std::thread::sleep(std::time::Duration::from_micros(delay_us));
                flag.store(true, Ordering::Relaxed);
            });
            world.advance(&mut controller, &mut tally, StopRequest::new(Some(&flag)))
        });
        match outcome {
            StepOutcome::Stopped => {
                assert!(bits(&world) == start, "{delay_us} µs: the stopped step moved the state");
            }
            StepOutcome::Accepted => {
                assert!(bits(&world) == after_one_step, "{delay_us} µs: another step");
            }
            other => panic!("{delay_us} µs: {other:?}"),
        }
    }
}

/// A sink that keeps nothing.
struct Nowhere;

impl FrameSink for Nowhere {
    fn record(&mut self, _: &hagfish_run::Frame<'_>) -> Result<(), hagfish_run::RunError> {
        Ok(())
    }
}

#[test]
fn a_run_asked_to_stop_ends_interrupted_after_its_first_frame() {
    let path = format!("{}/../../data/scenarios/form.ron", env!("CARGO_MANIFEST_DIR"));
    let loaded = LoadedScenario::load(&path).expect("form.ron loads");
    let stop = AtomicBool::new(true);
    let options = RunOptions { stop: Some(&stop), ..RunOptions::default() };
    let outcome = hagfish_run::run(&loaded, options, &mut Nowhere, &mut |_| {}).expect("runs");
    assert!(matches!(outcome.end, RunEnd::Interrupted), "{:?}", outcome.end);
    assert_eq!((outcome.summary.frames, outcome.summary.steps), (1, 0));
}
