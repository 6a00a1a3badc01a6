//! Static axial tension (`data/validation/tension.ron`): the straight rod pulled at the tail
//! along its axis by T. Every joint carries N = T: the pull passes through every joint axis, so
//! no joint moves and the backward pass sums exactly the load.

use std::path::Path;

use hagfish_scenario::LoadedScenario;

use crate::check::Check;
use crate::error::ValidationError;
use crate::settle::settle;

/// The scenario file, relative to the workspace root.
pub const SCENARIO: &str = "data/validation/tension.ron";

/// The largest relative difference between the tension at a joint and T.
pub fn axial(root: &Path) -> Result<Check, ValidationError> {
    let settled = settle(&LoadedScenario::load(root.join(SCENARIO))?)?;
    let t = settled.load.force_dyn;
    let worst = settled
        .world
        .data()
        .internal
        .loads
        .iter()
        .map(|load| (load.tension_dyn - t).abs())
        .fold(0.0, f64::max);
    Ok(Check {
        name: "axial tension".into(),
        setup: format!(
            "{}: N = {}; T = {t} dyn along the axis",
            settled.rod.name, settled.rod.body_count
        ),
        formula: "N(s) = T at every joint",
        source: "equilibrium of a straight rod",
        expected: t,
        measured: t + worst,
        unit: "dyn",
        tolerance: 1e-6,
    })
}
