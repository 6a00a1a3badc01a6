//! Scenario files (RON): which body, the time step and duration, drag, the phases of control,
//! and what to record. Paths inside a scenario are relative to the scenario file.
//!
//! ```ron
//! Scenario(
//!     name: "form",
//!     body: "../hagfish/es103.ron",
//!     time_step_s: 0.01,
//!     duration_s: 20.0,
//!     record_every_s: 0.1,
//!     drag: Some((linear_dyn_s_per_cm3: 0.0, quadratic_g_per_cm3: 0.5)),
//!     phases: [Form((gains: (...), steps: [...]))],
//! )
//! ```

use std::path::{Path, PathBuf};

use hagfish_anatomy::{AnatomyError, Biometrics, DataFile, Field};
use hagfish_control::{Phase, PhasedController, WaterDrag};
use hagfish_tree::State;
use serde::{Deserialize, Serialize};

use crate::error::SimError;
use crate::options::StepOptions;
use crate::world::World;

/// The content of a scenario file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// A short name, used in outputs.
    pub name: String,
    /// The biometrics file, relative to the scenario file.
    pub body: PathBuf,
    /// Time step h (s), > 0.
    pub time_step_s: f64,
    /// Simulated time (s), > 0.
    pub duration_s: f64,
    /// Interval between recorded frames (s); frame 0 is the initial state.
    #[serde(default = "default_record_every")]
    pub record_every_s: f64,
    /// Water drag on the body, or `None` for a body in vacuum.
    #[serde(default)]
    pub drag: Option<WaterDrag>,
    /// The phases of control, in order.
    pub phases: Vec<Phase>,
}

fn default_record_every() -> f64 {
    0.1
}

/// A scenario with its biometrics loaded and checked.
#[derive(Clone, Debug)]
pub struct LoadedScenario {
    /// The scenario as read.
    pub scenario: Scenario,
    /// The body's biometrics.
    pub biometrics: Biometrics,
    /// The scenario file's path.
    pub path: PathBuf,
}

impl LoadedScenario {
    /// Reads the scenario at `path`, checks its values (each error at its `file:line:column`)
    /// and loads the biometrics it names.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, SimError> {
        let file = DataFile::<Scenario>::read(path.as_ref())?;
        validate(&file)?;
        let directory = file.path.parent().unwrap_or(Path::new("."));
        let biometrics = Biometrics::load(directory.join(&file.value.body))?;
        Ok(Self { scenario: file.value, biometrics, path: file.path })
    }

    /// The world at rest and the scenario's controller, ready to run.
    pub fn build(&self) -> Result<(World, PhasedController), SimError> {
        let model = self.biometrics.to_model()?;
        let state = State::rest(&model);
        let options =
            StepOptions { time_step: self.scenario.time_step_s, ..StepOptions::default() };
        let world = World::new(model, options, state)?;
        let controller = PhasedController::new(self.scenario.drag, self.scenario.phases.clone());
        Ok((world, controller))
    }

    /// The world and controller after running the scenario from rest to time `time_s`
    /// (rounded to whole steps; no recording): e.g. the knotted state of the benchmarks.
    pub fn build_at(&self, time_s: f64) -> Result<(World, PhasedController), SimError> {
        let (mut world, mut controller) = self.build()?;
        let steps = (time_s / self.scenario.time_step_s).round() as u64;
        for _ in 0..steps {
            world.step(&mut controller)?;
        }
        Ok((world, controller))
    }
}

fn validate(file: &DataFile<Scenario>) -> Result<(), AnatomyError> {
    let s = &file.value;
    let positive = |name: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(AnatomyError::OutOfRange {
                at: file.locate(&Field::whole(name)),
                field: Field::whole(name),
                value,
                expected: "finite and > 0".into(),
            })
        }
    };
    positive("time_step_s", s.time_step_s)?;
    positive("duration_s", s.duration_s)?;
    positive("record_every_s", s.record_every_s)?;
    if let Some(drag) = s.drag {
        for (name, value) in [
            ("linear_dyn_s_per_cm3", drag.linear_dyn_s_per_cm3),
            ("quadratic_g_per_cm3", drag.quadratic_g_per_cm3),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(AnatomyError::OutOfRange {
                    at: file.locate(&Field::whole(name)),
                    field: Field::whole(name),
                    value,
                    expected: "finite and ≥ 0".into(),
                });
            }
        }
    }
    Ok(())
}
