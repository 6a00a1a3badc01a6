//! `cargo xtask knotted`: the knotted benchmark state (`hagfish_bench_support::knotted_world`), exported
//! for the peer comparison (`bench/peers/`) and timed step by step.
//!
//! - `--export PATH`: writes the model (bodies, joints, DOF parameters) and the state (t, q,
//!   q̇, body centres) as JSON, DOFs in hagfish order (joint 0 first; a universal joint's Y
//!   then Z).
//! - timing: from the knotted state, `--repeat` runs of `--steps` steps at `--time-step` with
//!   a passive body (no drag, no controller: the physics a peer simulator can reproduce);
//!   the `--backend` (sparse maximal by default); prints the median and minimum wall time
//!   per step, the median per stage, the contacts, whether every run stayed finite and how
//!   far any body centre moved, as one JSON object.

use std::path::Path;
use std::time::Instant;

use hagfish_bench_support::{KNOTTED_SCENARIO, KNOTTED_TIME_S, knotted_world};
use hagfish_control::Passive;
use hagfish_sim::{DynamicsBackend, StageTimings, StepOptions, World};
use hagfish_tree::{JointKind, Model, State};
use serde::{Serialize, Serializer};

/// What to do with the knotted state.
pub struct Request<'a> {
    /// Where to write the JSON export, if anywhere.
    pub export: Option<&'a Path>,
    /// Steps per timed run (0: no timing).
    pub steps: usize,
    /// Timed runs.
    pub repeat: usize,
    /// Time step of the timed runs (s).
    pub time_step: f64,
    /// Dynamics backend of the timed runs.
    pub backend: DynamicsBackend,
}

/// Runs the request in workspace `root`.
pub fn run(root: &Path, request: &Request<'_>) -> Result<(), String> {
    let (world, _) = knotted_world(root).map_err(|e| e.to_string())?;
    if let Some(path) = request.export {
        let mut world = world;
        let json = serde_json::to_string(&export(&mut world)).map_err(|e| e.to_string())?;
        std::fs::write(path, json + "\n").map_err(|e| format!("{}: {e}", path.display()))?;
        eprintln!("wrote {}", path.display());
        return time(&world, request);
    }
    time(&world, request)
}

/// Median of `values` (sorted in place); 0 for none.
fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(0.0)
}

/// `seconds` in microseconds, to 0.01 µs (the resolution worth printing).
fn microseconds(seconds: f64) -> f64 {
    (1e8 * seconds).round() / 100.0
}

/// The seconds of every step, per stage of [`StageTimings::stages`], in pipeline order.
struct StageSamples(Vec<(&'static str, Vec<f64>)>);

impl StageSamples {
    /// One empty list per stage, so that no stage can be left out.
    fn new() -> Self {
        Self(StageTimings::default().stages().map(|(name, _)| (name, Vec::new())).into())
    }

    /// Adds one step's timings.
    fn push(&mut self, timings: &StageTimings) {
        for ((_, all), (_, seconds)) in self.0.iter_mut().zip(timings.stages()) {
            all.push(seconds);
        }
    }

    /// The median per stage in µs.
    fn medians_us(&mut self) -> StageMedians {
        StageMedians(
            self.0.iter_mut().map(|(name, all)| (*name, microseconds(median(all)))).collect(),
        )
    }
}

/// Median µs per stage, written as a JSON object in pipeline order.
struct StageMedians(Vec<(&'static str, f64)>);

impl Serialize for StageMedians {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_map(self.0.iter().copied())
    }
}

/// The timing's JSON object, read by `bench/peers/compare.py`.
#[derive(Serialize)]
struct Timing {
    simulator: &'static str,
    state: String,
    time_step: f64,
    steps: usize,
    repeat: usize,
    median_us_per_step: f64,
    min_us_per_step: f64,
    steps_per_second: f64,
    median_contacts: f64,
    max_contacts: f64,
    failed_runs: usize,
    max_abs_qdot: f64,
    max_centre_displacement_cm: f64,
    median_stage_us: StageMedians,
}

/// Times `request.repeat` runs of `request.steps` passive steps from the state of `world`.
fn time(world: &World, request: &Request<'_>) -> Result<(), String> {
    if request.steps == 0 {
        return Ok(());
    }
    let knotted = world.state().clone();
    let options = StepOptions {
        time_step: request.time_step,
        backend: request.backend,
        ..world.options().clone()
    };
    let mut timed =
        World::new(world.model().clone(), options, knotted.clone()).map_err(|e| e.to_string())?;
    let (mut per_step, mut contacts) = (Vec::new(), Vec::new());
    let mut stages = StageSamples::new();
    let mut failures = 0;
    let (mut max_rate, mut displacement): (f64, f64) = (0.0, 0.0);
    let (mut start_centres, mut centres) = (Vec::new(), Vec::new());
    timed.body_centres(&mut start_centres);
    for _ in 0..request.repeat {
        timed.set_state(knotted.clone()).map_err(|e| e.to_string())?;
        for _ in 0..request.steps {
            let start = Instant::now();
            let report = match timed.step(&mut Passive) {
                Ok(report) => *report,
                Err(_) => {
                    failures += 1;
                    break;
                }
            };
            per_step.push(start.elapsed().as_secs_f64());
            contacts.push(report.self_contacts as f64);
            stages.push(&report.timings);
        }
        max_rate = timed.state().qdot.iter().fold(max_rate, |m, v| m.max(v.abs()));
        timed.body_centres(&mut centres);
        let moved = centres.iter().zip(&start_centres).map(|(a, b)| a.distance(*b));
        displacement = moved.fold(displacement, f64::max);
    }
    let min = per_step.iter().copied().fold(f64::INFINITY, f64::min);
    let median_step = median(&mut per_step);
    let timing = Timing {
        simulator: match request.backend {
            DynamicsBackend::DenseReduced => "hagfish dense",
            DynamicsBackend::SparseMaximal => "hagfish sparse",
        },
        state: format!("{KNOTTED_SCENARIO} at t = {KNOTTED_TIME_S} s"),
        time_step: request.time_step,
        steps: request.steps,
        repeat: request.repeat,
        median_us_per_step: microseconds(median_step),
        min_us_per_step: microseconds(min),
        steps_per_second: (1.0 / median_step).round(),
        median_contacts: median(&mut contacts),
        max_contacts: contacts.iter().copied().fold(0.0, f64::max),
        failed_runs: failures,
        max_abs_qdot: max_rate,
        max_centre_displacement_cm: displacement,
        median_stage_us: stages.medians_us(),
    };
    println!("{}", serde_json::to_string(&timing).map_err(|e| e.to_string())?);
    Ok(())
}

/// The export's JSON object, read by `bench/peers/`: model and state in CGS units, radians.
#[derive(Serialize)]
struct Export {
    source: String,
    units: &'static str,
    gravity: [f64; 3],
    bodies: Vec<BodyJson>,
    joints: Vec<JointJson>,
    dofs: Vec<DofJson>,
    t: f64,
    q: Vec<f64>,
    qdot: Vec<f64>,
    centres: Vec<[f64; 3]>,
    self_contacts: usize,
}

/// One body of [`Export`].
#[derive(Serialize)]
struct BodyJson {
    mass: f64,
    principal_inertia: [f64; 3],
    offset: [f64; 3],
    radius: f64,
    length: f64,
}

/// One joint of [`Export`]; `rotation` is its offset's matrix by columns (x, y, z axes).
#[derive(Serialize)]
struct JointJson {
    kind: KindJson,
    parent: Option<usize>,
    offset: [f64; 3],
    rotation: [[f64; 3]; 3],
    dof_start: usize,
}

/// A joint's kind: `"fixed"`, `{"revolute": axis}`, `"universal_yz"` or `"translation"`.
#[derive(Serialize)]
#[serde(rename_all = "snake_case")]
enum KindJson {
    Fixed,
    Revolute([f64; 3]),
    UniversalYz,
    Translation,
}

/// One DOF of [`Export`]; an infinite limit is written as `null` (serde_json's way).
#[derive(Serialize)]
struct DofJson {
    stiffness: f64,
    damping: f64,
    rest: f64,
    lower: f64,
    upper: f64,
}

/// The model and current state of `world` (CGS units, radians).
fn export(world: &mut World) -> Export {
    let mut centres = Vec::new();
    world.body_centres(&mut centres);
    let model: &Model = world.model();
    let state: &State = world.state();
    let bodies = model.bodies().iter().map(|b| BodyJson {
        mass: b.mass,
        principal_inertia: b.principal_inertia.to_array(),
        offset: b.offset.translation.to_array(),
        radius: b.radius,
        length: b.length,
    });
    let joints = model.joints().iter().map(|j| {
        let r = j.offset.rotation;
        JointJson {
            kind: match j.kind {
                JointKind::Fixed => KindJson::Fixed,
                JointKind::Revolute { axis } => KindJson::Revolute(axis.to_array()),
                JointKind::UniversalYz => KindJson::UniversalYz,
                JointKind::Translation => KindJson::Translation,
            },
            parent: j.parent,
            offset: j.offset.translation.to_array(),
            rotation: [r.x_axis, r.y_axis, r.z_axis].map(|axis| axis.to_array()),
            dof_start: j.dof_start,
        }
    });
    let dofs = model.dofs().iter().map(|d| DofJson {
        stiffness: d.stiffness,
        damping: d.damping,
        rest: d.rest,
        lower: d.lower,
        upper: d.upper,
    });
    Export {
        source: format!("{KNOTTED_SCENARIO} at t = {KNOTTED_TIME_S} s (cargo xtask knotted)"),
        units: "cm, g, s, rad (cm for a translation); joint rotation matrices column-major (x, y, z axes)",
        gravity: model.gravity().to_array(),
        bodies: bodies.collect(),
        joints: joints.collect(),
        dofs: dofs.collect(),
        t: state.t,
        q: state.q.clone(),
        qdot: state.qdot.clone(),
        centres: centres.iter().map(|c| c.to_array()).collect(),
        self_contacts: world.data().report.self_contacts,
    }
}

#[cfg(test)]
mod tests {
    use hagfish_sim::Stage;

    use super::*;

    /// Every stage of [`StageTimings::stages`] has its median in the JSON, in pipeline order
    /// (seven buffers for nine stages once dropped `integrate` and `check`).
    #[test]
    fn the_timing_json_has_every_stage() {
        let mut timings = StageTimings::default();
        timings.add(Stage::Integrate, 3e-6);
        timings.add(Stage::Check, 4e-6);
        let mut samples = StageSamples::new();
        samples.push(&timings);
        let json = serde_json::to_value(samples.medians_us()).expect("serialises");
        let written: Vec<&String> = json.as_object().expect("an object").keys().collect();
        let stages = timings.stages();
        assert_eq!(written.len(), stages.len(), "{json}");
        for (name, seconds) in stages {
            assert_eq!(json[name], microseconds(seconds), "{name} in {json}");
        }
        assert_eq!((json["integrate"].as_f64(), json["check"].as_f64()), (Some(3.0), Some(4.0)));
        let text = serde_json::to_string(&samples.medians_us()).expect("serialises");
        assert!(text.starts_with("{\"kinematics\":") && text.ends_with("\"check\":4.0}"), "{text}");
    }
}
