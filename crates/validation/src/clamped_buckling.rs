//! A clamped–clamped rod buckled by a grip (`data/validation/clamped_buckling.ron`): the head
//! held along +X, the tail gripped (clamped) and pushed toward the head at a slow prescribed
//! speed (`hagfish_control::PullPhase`). Past Euler's load the rod bends out and the force
//! the grip needs stays at `P = 4π²B/L²`, the clamped–clamped buckling load: a check of the
//! grip's rows and of the force read off their multipliers
//! ([`hagfish_sim::rows::grip_wrench`]) against a formula.

use std::path::Path;

use hagfish_anatomy::Body;
use hagfish_scenario::LoadedScenario;
use hagfish_sim::rows::grip_wrench;

use crate::check::Check;
use crate::error::ValidationError;

/// The scenario file, relative to the workspace root.
pub const SCENARIO: &str = "data/validation/clamped_buckling.ron";

/// The grip's force along the push (dyn) against the end shortening over L, sampled each
/// step of the push.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Buckling {
    /// Euler's load `4π²B/L²` of the rod (dyn).
    pub euler_load_dyn: f64,
    /// The rod, its bodies and the push, in words (for the check's set-up).
    pub setup: String,
    /// `(Δ/L, P)`: the shortening of the head-to-tail distance over L and the grip's
    /// compressive force (dyn), one per step.
    pub samples: Vec<(f64, f64)>,
}

/// Runs the scenario with the rod cut into `bodies` bodies and samples the push.
pub fn run(root: &Path, bodies: usize) -> Result<Buckling, ValidationError> {
    let mut loaded = LoadedScenario::load(root.join(SCENARIO))?;
    let Body::Rod(rod) = &mut loaded.body else {
        return Err(ValidationError::Scenario {
            path: loaded.path.clone(),
            reason: "its body is not a rod".into(),
        });
    };
    rod.body_count = bodies;
    let (length, stiffness) = (rod.length_cm, rod.bending_stiffness_dyn_cm2);
    let speed = loaded.scenario.phases.iter().find_map(|phase| match phase {
        hagfish_control::Phase::Pull(pull) if pull.speed_cm_per_s > 0.0 => {
            Some(pull.speed_cm_per_s)
        }
        _ => None,
    });
    let setup = format!(
        "{}: L = {length} cm, B = {stiffness} dyn·cm², N = {bodies}; tail gripped and pushed at {} cm/s; Δ = 1 % L",
        rod.name,
        speed.unwrap_or(0.0)
    );
    let (mut world, mut controller) = loaded.build()?;
    let h = loaded.scenario.time_step_s;
    let steps = (loaded.scenario.duration_s / h).round() as u64;
    let mut samples = Vec::new();
    while world.steps() < steps && !controller.finished() {
        world.step(&mut controller)?;
        let data = world.data();
        let Some(grip) = data.actuation.grip else { continue };
        let (force, _) = grip_wrench(&data.rows, data.solver.multipliers(), h);
        samples.push(((length - grip.point.x) / length, -force.x));
    }
    let euler_load_dyn = 4.0 * std::f64::consts::PI.powi(2) * stiffness / (length * length);
    Ok(Buckling { euler_load_dyn, setup, samples })
}

impl Buckling {
    /// The force at the last sample whose shortening is at most `shortening` (of L).
    pub fn force_at(&self, shortening: f64) -> Option<f64> {
        self.samples.iter().rev().find(|(d, _)| *d <= shortening).map(|&(_, p)| p)
    }

    /// The check: the force at 1 % shortening against Euler's load, within 2 %.
    pub fn check(&self) -> Check {
        Check {
            name: "clamped–clamped buckling under a grip: the force".into(),
            setup: self.setup.clone(),
            formula: "P = 4π²B/L²",
            source: "Euler's buckling load, both ends clamped",
            expected: self.euler_load_dyn,
            measured: self.force_at(0.01).unwrap_or(f64::NAN),
            unit: "dyn",
            tolerance: 0.02,
        }
    }
}
