//! The knotted state that the benchmarks, the allocation test and the peer comparison step:
//! `data/scenarios/form.ron` run from rest to t = 23.13 s on the default (sparse) backend,
//! where the tightened trefoil has 40 self contacts (41 on the dense backend, where the time
//! was chosen as the most contacts of any step between 19 and 30 s; the state is the end of a
//! 2313-step run, so any change of rounding in a step moves it a little: the benchmarks print
//! the count).

use std::path::Path;

use hagfish_control::PhasedController;
use hagfish_scenario::ScenarioError;
use hagfish_scenario::{LoadedScenario, Override};
use hagfish_sim::World;

/// The scenario of the knotted benchmark state, relative to the workspace root.
pub const KNOTTED_SCENARIO: &str = "data/scenarios/form.ron";

/// Simulated time of the knotted benchmark state (s).
pub const KNOTTED_TIME_S: f64 = 23.13;

/// The world (and the scenario's controller) at the knotted benchmark state, with the
/// scenario loaded from `workspace_root`.
pub fn knotted_world(workspace_root: &Path) -> Result<(World, PhasedController), ScenarioError> {
    LoadedScenario::load(workspace_root.join(KNOTTED_SCENARIO))?.build_at(KNOTTED_TIME_S)
}

/// The body count of the long knotted state: ES103 at this resolution (D16: the same animal,
/// bodies 0.42 mm long).
pub const LONG_KNOTTED_BODIES: usize = 1000;

/// Simulated time of the long knotted state (s): `tie.ron` has tied its trefoil at 17.8 s on
/// this body and holds it, with 25–44 self contacts.
pub const LONG_KNOTTED_TIME_S: f64 = 19.0;

/// The world (sparse backend) and controller of `data/scenarios/tie.ron` on ES103 at
/// [`LONG_KNOTTED_BODIES`] bodies at [`LONG_KNOTTED_TIME_S`]: a trefoil tied by control in a
/// long chain. The body file is written into `scratch` (a directory of the caller's).
///
/// # Errors
/// The file's I/O error, or the [`ScenarioError`] of loading the scenario or stepping to the state.
pub fn long_knotted_world(
    workspace_root: &Path,
    scratch: &Path,
) -> Result<(World, PhasedController), Box<dyn std::error::Error>> {
    let es103 = std::fs::read_to_string(workspace_root.join("data/hagfish/es103.ron"))?;
    let body = scratch.join(format!("es103_{LONG_KNOTTED_BODIES}_bodies.ron"));
    let long = es103.replace(" body_count: 100,", &format!(" body_count: {LONG_KNOTTED_BODIES},"));
    std::fs::write(&body, long)?;
    let overrides = [
        Override { path: "body".into(), value: format!("{:?}", body.display().to_string()) },
        Override { path: "backend".into(), value: "SparseMaximal".into() },
    ];
    let tie = LoadedScenario::load_with(workspace_root.join("data/scenarios/tie.ron"), &overrides)?;
    Ok(tie.build_at(LONG_KNOTTED_TIME_S)?)
}
