//! The knotted state that the benchmarks, the allocation test and the peer comparison step:
//! `data/scenarios/form.ron` run from rest to t = 23.13 s, where the tightened trefoil has 41
//! self contacts (the most of any step between 19 and 30 s when chosen, after the narrow
//! phase's chord-start search changed the run; the state is the end of a 2313-step run, so
//! any change of rounding in a step moves it a little: the benchmarks print the count).

use std::path::Path;

use hagfish_control::PhasedController;
use hagfish_sim::{LoadedScenario, SimError, World};

/// The scenario of the knotted benchmark state, relative to the workspace root.
pub const KNOTTED_SCENARIO: &str = "data/scenarios/form.ron";

/// Simulated time of the knotted benchmark state (s).
pub const KNOTTED_TIME_S: f64 = 23.13;

/// The world (and the scenario's controller) at the knotted benchmark state, with the
/// scenario loaded from `workspace_root`.
pub fn knotted_world(workspace_root: &Path) -> Result<(World, PhasedController), SimError> {
    LoadedScenario::load(workspace_root.join(KNOTTED_SCENARIO))?.build_at(KNOTTED_TIME_S)
}
