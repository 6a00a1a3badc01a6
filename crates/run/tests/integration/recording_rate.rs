//! How often frames are recorded does not change the run: the controller observes the knot
//! (the analysis that ends a tie, the core the `core_*` end conditions read) every
//! `observe_every_s`, not at the recorded frames. Before that split, `thesis.ron` took 2471,
//! 2601 and 2466 steps with frames every 0.1, 0.5 and 0.05 s (its phases ended at other
//! times).

use hagfish_run::{Frame, FrameSink, RunEnd, RunError};
use hagfish_scenario::{LoadedScenario, Override};

/// The times of the recorded frames.
#[derive(Default)]
struct Times(Vec<f64>);

impl FrameSink for Times {
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), RunError> {
        self.0.push(frame.time);
        Ok(())
    }
}

/// What a run of `scenario` (in `data/scenarios`) with `overrides` ends as: its end, final
/// state (q and q̇ bits) and frame times.
fn run(scenario: &str, overrides: &[(&str, &str)]) -> (RunEnd, Vec<u64>, Vec<f64>) {
    let overrides: Vec<Override> = overrides
        .iter()
        .map(|(path, value)| Override { path: (*path).into(), value: (*value).into() })
        .collect();
    let path = format!("{}/../../data/scenarios/{scenario}", env!("CARGO_MANIFEST_DIR"));
    let loaded = LoadedScenario::load_with(&path, &overrides).expect("the scenario loads");
    let mut times = Times::default();
    let outcome = hagfish_run::run(&loaded, Default::default(), &mut times, &mut |_| {})
        .expect("the run starts");
    let bits = outcome.state.q.iter().chain(&outcome.state.qdot).map(|x| x.to_bits()).collect();
    (outcome.end, bits, times.0)
}

#[test]
fn the_recording_rate_leaves_the_run_unchanged_and_the_observation_rate_does_not() {
    // The trefoil is shown at ≈ 17.2 s, the tie phase ends after 0.5 s of observations
    // showing it, and the tighten phase's targets take over.
    let duration = ("duration_s", "19.0");
    let (end, every_tenth, tenths) = run("thesis.ron", &[duration]);
    assert!(matches!(end, RunEnd::Completed), "{end:?}");
    assert_eq!(tenths.len(), 191);
    for record_every in ["0.05", "0.37"] {
        let (end, state, _) = run("thesis.ron", &[duration, ("record_every_s", record_every)]);
        assert!(matches!(end, RunEnd::Completed), "{end:?}");
        assert!(state == every_tenth, "frames every {record_every} s changed the run");
    }
    let (_, observed_less, _) = run("thesis.ron", &[duration, ("observe_every_s", "0.3")]);
    assert!(observed_less != every_tenth, "observing every 0.3 s ends the tie phase elsewhere");
}

#[test]
fn a_failed_tie_is_recorded_where_it_failed_between_frames() {
    // The crossover 0.85 L from the head leaves too little tail to tie
    // (tests/integration/tie_family.rs).
    let (end, _, times) = run(
        "tie.ron",
        &[("phases[0].Tie.at", "0.85"), ("phases[0].Tie.attempts", "1"), ("record_every_s", "1.0")],
    );
    assert!(matches!(end, RunEnd::TieFailed(_)), "{end:?}");
    let last = *times.last().expect("frames");
    let before = times[times.len() - 2];
    assert!(
        last > before && last < before + 1.0,
        "the failure's frame at {last} s, after {before} s"
    );
    assert!((last * 10.0 - (last * 10.0).round()).abs() < 1e-6, "on an observation: {last} s");
}
