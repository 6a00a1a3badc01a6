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

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use hagfish_bench_support::{KNOTTED_SCENARIO, KNOTTED_TIME_S, knotted_world};
use hagfish_control::Passive;
use hagfish_sim::{DynamicsBackend, StepOptions, World};
use hagfish_tree::{JointKind, Model, State};

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
        let json = export(&mut world);
        std::fs::write(path, json).map_err(|e| format!("{}: {e}", path.display()))?;
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
    let mut stages: Vec<Vec<f64>> = vec![Vec::new(); 7];
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
            for (all, (_, seconds)) in stages.iter_mut().zip(report.timings.stages()) {
                all.push(seconds);
            }
        }
        max_rate = timed.state().qdot.iter().fold(max_rate, |m, v| m.max(v.abs()));
        timed.body_centres(&mut centres);
        let moved = centres.iter().zip(&start_centres).map(|(a, b)| a.distance(*b));
        displacement = moved.fold(displacement, f64::max);
    }
    let min = per_step.iter().copied().fold(f64::INFINITY, f64::min);
    let median_step = median(&mut per_step);
    let names = hagfish_sim::StageTimings::default().stages().map(|(name, _)| name);
    let mut stage_json = String::new();
    for (i, (name, all)) in names.iter().zip(&mut stages).enumerate() {
        let separator = if i == 0 { "" } else { ", " };
        let _ = write!(stage_json, "{separator}\"{name}\": {:.2}", 1e6 * median(all));
    }
    let simulator = match request.backend {
        DynamicsBackend::DenseReduced => "hagfish dense",
        DynamicsBackend::SparseMaximal => "hagfish sparse",
    };
    println!(
        "{{\"simulator\": \"{simulator}\", \"state\": \"{KNOTTED_SCENARIO} at t = {KNOTTED_TIME_S} s\", \
\"time_step\": {}, \"steps\": {}, \"repeat\": {}, \"median_us_per_step\": {:.2}, \
\"min_us_per_step\": {:.2}, \"steps_per_second\": {:.0}, \"median_contacts\": {}, \
\"max_contacts\": {}, \"failed_runs\": {failures}, \"max_abs_qdot\": {:.4e}, \
\"max_centre_displacement_cm\": {displacement:.4}, \
\"median_stage_us\": {{{stage_json}}}}}",
        request.time_step,
        request.steps,
        request.repeat,
        1e6 * median_step,
        1e6 * min,
        1.0 / median_step,
        median(&mut contacts),
        contacts.iter().copied().fold(0.0, f64::max),
        max_rate,
    );
    Ok(())
}

fn vector(v: glam::DVec3) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

fn list(values: impl Iterator<Item = String>) -> String {
    format!("[{}]", values.collect::<Vec<_>>().join(", "))
}

/// The model and current state of `world` as JSON (CGS units, radians).
fn export(world: &mut World) -> String {
    let mut centres = Vec::new();
    world.body_centres(&mut centres);
    let model: &Model = world.model();
    let state: &State = world.state();
    let bodies = model.bodies().iter().map(|b| {
        format!(
            "{{\"mass\": {:?}, \"principal_inertia\": {}, \"offset\": {}, \"radius\": {:?}, \
\"length\": {:?}}}",
            b.mass,
            vector(b.principal_inertia),
            vector(b.offset.translation),
            b.radius,
            b.length
        )
    });
    let joints = model.joints().iter().map(|j| {
        let kind = match j.kind {
            JointKind::Fixed => "\"fixed\"".to_owned(),
            JointKind::Revolute { axis } => format!("{{\"revolute\": {}}}", vector(axis)),
            JointKind::UniversalYz => "\"universal_yz\"".to_owned(),
        };
        let r = j.offset.rotation;
        format!(
            "{{\"kind\": {kind}, \"parent\": {}, \"offset\": {}, \"rotation\": {}, \
\"dof_start\": {}}}",
            j.parent.map_or("null".to_owned(), |p| p.to_string()),
            vector(j.offset.translation),
            list([r.x_axis, r.y_axis, r.z_axis].into_iter().map(vector)),
            j.dof_start
        )
    });
    let finite = |x: f64| if x.is_finite() { format!("{x:?}") } else { "null".to_owned() };
    let dofs = model.dofs().iter().map(|d| {
        format!(
            "{{\"stiffness\": {:?}, \"damping\": {:?}, \"rest\": {:?}, \"lower\": {}, \
\"upper\": {}}}",
            d.stiffness,
            d.damping,
            d.rest,
            finite(d.lower),
            finite(d.upper)
        )
    });
    let numbers = |v: &[f64]| list(v.iter().map(|x| format!("{x:?}")));
    format!(
        "{{\n\"source\": \"{KNOTTED_SCENARIO} at t = {KNOTTED_TIME_S} s (cargo xtask knotted)\",\n\
\"units\": \"cm, g, s, rad; joint rotation matrices column-major (x, y, z axes)\",\n\
\"gravity\": {},\n\"bodies\": {},\n\"joints\": {},\n\"dofs\": {},\n\"t\": {:?},\n\"q\": {},\n\
\"qdot\": {},\n\"centres\": {},\n\"self_contacts\": {}\n}}\n",
        vector(model.gravity()),
        list(bodies),
        list(joints),
        list(dofs),
        state.t,
        numbers(&state.q),
        numbers(&state.qdot),
        list(centres.iter().copied().map(vector)),
        world.data().report.self_contacts,
    )
}
