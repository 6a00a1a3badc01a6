//! A cantilever: the rod clamped at the head along +X (root joint and head rows), a dead load
//! P along +Y on the tail end (`data/validation/cantilever.ron`).
//!
//! - Small load: the tip deflects by `PL³/(3B)` (Euler–Bernoulli). The chain's midpoint rule
//!   (bend joints 2ℓ apart, `k = B/2ℓ`) gives `PL³/(3B)·(1 − 1/N²)`, so the error falls as
//!   1/N² (measured at N = 20, 50, 100).
//! - The same run's internal bending moment at every joint against statics: the load's moment
//!   about the joint, `P (x_tip − x_j)`, from the deflected positions.
//! - Large load `α = PL²/B`: the tip against the inextensible elastica ([`elastica_tip`]).

use std::path::Path;

use glam::DVec3;
use hagfish_anatomy::Body;
use hagfish_control::Phase;
use hagfish_scenario::LoadedScenario;

use crate::check::Check;
use crate::elastica::elastica_tip;
use crate::error::ValidationError;
use crate::settle::{Settled, settle};

/// The scenario file, relative to the workspace root.
pub const SCENARIO: &str = "data/validation/cantilever.ron";

/// The cantilever scenario with the rod cut into `bodies` bodies and, if given, the load
/// `force_dyn`.
fn scenario(
    root: &Path,
    bodies: usize,
    force_dyn: Option<f64>,
) -> Result<LoadedScenario, ValidationError> {
    let mut loaded = LoadedScenario::load(root.join(SCENARIO))?;
    if let Body::Rod(rod) = &mut loaded.body {
        rod.body_count = bodies;
    }
    if let (Some(force), Some(Phase::Load(load))) = (force_dyn, loaded.scenario.phases.first_mut())
    {
        load.force_dyn = force;
    }
    Ok(loaded)
}

/// The small-load checks at `bodies` bodies: the tip deflection and the bending moment.
pub fn small_load(root: &Path, bodies: usize) -> Result<[Check; 2], ValidationError> {
    let settled = settle(&scenario(root, bodies, None)?)?;
    let (rod, p) = (&settled.rod, settled.load.force_dyn);
    let (l, b) = (rod.length_cm, rod.bending_stiffness_dyn_cm2);
    let setup =
        format!("{}: L = {l} cm, B = {b} dyn·cm², N = {bodies}; P = {p} dyn ⊥, settled", rod.name);
    let deflection = Check {
        name: "cantilever, small load: tip deflection".into(),
        setup: setup.clone(),
        formula: "δ = PL³/(3B)",
        source: "Euler–Bernoulli beam theory",
        expected: p * l.powi(3) / (3.0 * b),
        measured: settled.tail_end().y,
        unit: "cm",
        tolerance: 0.02,
    };
    let moment = Check {
        name: "cantilever: internal bending moment".into(),
        setup,
        formula: "max over joints of abs(m_z − P(x_tip − x_j)) / PL",
        source: "statics of the deflected rod",
        expected: 0.0,
        measured: worst_moment_error(&settled),
        unit: "",
        tolerance: 1e-6,
    };
    Ok([deflection, moment])
}

/// The largest difference, over the joints, between the internal bending moment about z and
/// the load's moment about the joint, relative to PL.
fn worst_moment_error(settled: &Settled) -> f64 {
    let data = settled.world.data();
    let tip = settled.tail_end();
    let p = settled.load.force_dyn;
    let scale = p * settled.rod.length_cm;
    let load = DVec3::new(0.0, p, 0.0);
    data.internal
        .loads
        .iter()
        .enumerate()
        .map(|(j, internal)| {
            let frame = &data.tree.joint_frames[j];
            let statics = (tip - frame.translation).cross(load);
            let body_z = frame.rotation.col(2);
            (internal.bend_z_dyn_cm - statics.dot(body_z)).abs() / scale
        })
        .fold(0.0, f64::max)
}

/// The large-load check: `α = PL²/B`, the tip against the elastica's (both coordinates, the
/// distance relative to L).
pub fn large_load(root: &Path, alpha: f64) -> Result<Check, ValidationError> {
    let base = scenario(root, 100, None)?;
    let Body::Rod(rod) = &base.body else {
        return Err(ValidationError::Scenario {
            path: base.path.clone(),
            reason: "its body is not a rod".into(),
        });
    };
    let (l, b) = (rod.length_cm, rod.bending_stiffness_dyn_cm2);
    let p = alpha * b / (l * l);
    let settled = settle(&scenario(root, 100, Some(p))?)?;
    let (x, y) = elastica_tip(alpha);
    let tip = settled.tail_end() / l;
    let distance = (tip.x - x).hypot(tip.y - y);
    Ok(Check {
        name: "cantilever, large load: tip position".into(),
        setup: format!("{}: N = 100; PL²/B = {alpha} (P = {p:.4} dyn ⊥), settled", rod.name),
        formula: "elastica Bθ'' = −P cos θ, θ(0) = 0, θ'(L) = 0 (shooting)",
        source: "Euler's inextensible elastica, solved in `elastica.rs`",
        expected: y,
        measured: y + distance.copysign(tip.y - y),
        unit: "L",
        tolerance: 0.02,
    })
}
