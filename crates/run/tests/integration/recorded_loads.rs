//! The joint loads of a recorded frame do not depend on how often frames are recorded: the run
//! computes them only for the steps that end on a frame (they feed nothing back), and a run
//! recording every step, which computes them on every step, records the same loads, bit for
//! bit, at the common frames.

use hagfish_run::{Frame, FrameSink, RunError};
use hagfish_scenario::{LoadedScenario, Override};
use hagfish_sim::JointLoad;

/// The time and joint loads of every frame.
#[derive(Default)]
struct Loads(Vec<(f64, Vec<JointLoad>)>);

impl FrameSink for Loads {
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), RunError> {
        self.0.push((frame.time, frame.internal.to_vec()));
        Ok(())
    }
}

/// `form.ron` (the scripted tail pull: loads change every step) for 1.5 s, recording every
/// `record_every_s`.
fn loads(record_every_s: &str) -> Vec<(f64, Vec<JointLoad>)> {
    let set = |path: &str, value: &str| Override { path: path.into(), value: value.into() };
    let overrides = [set("duration_s", "1.5"), set("record_every_s", record_every_s)];
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/form.ron");
    let loaded = LoadedScenario::load_with(path, &overrides).expect("form.ron loads");
    let mut sink = Loads::default();
    let outcome = hagfish_run::run(&loaded, Default::default(), &mut sink, &mut |_| {})
        .expect("the run starts");
    outcome.finished().expect("the run completes");
    sink.0
}

#[test]
fn recorded_joint_loads_do_not_depend_on_the_recording_rate() {
    let every_step = loads("0.01");
    let every_tenth = loads("0.1");
    assert_eq!(every_step.len(), 151);
    assert_eq!(every_tenth.len(), 16);
    for (k, (time, frame)) in every_tenth.iter().enumerate().skip(1) {
        let (same_time, same) = &every_step[10 * k];
        assert_eq!(time, same_time);
        let differing = frame.iter().zip(same).position(|(a, b)| a != b);
        assert_eq!(differing, None, "the first joint whose load differs at t = {time} s");
        assert!(frame.iter().any(|l| l.tension_dyn != 0.0), "loads at t = {time} s");
    }
}
