//! A run directory's thigmotaxic force field with what places it in time and along the body:
//! `thigmo_force.npy`, the `time_s`, `phase` and `knot_core_start_cm` columns of
//! `metrics.csv`, and the DOFs' kinds and arc lengths from the body file `scenario.ron` names.

use std::path::{Path, PathBuf};

use hagfish_report::Metrics;
use hagfish_run::npy::read_npy;
use hagfish_scenario::LoadedScenario;

use crate::error::ModesError;
use crate::field::Field;
use hagfish_control::{DofKind, KindSelection};

/// The whole recorded force field of a run and its frames' times, phases and knot positions.
/// The DOFs' arc lengths are those the run itself uses (`hagfish_sim::dof_arc_lengths`: joint
/// i halfway between body centres i − 1 and i, from the head body's centre), computed exactly
/// from the body file at q = 0, the straight rest shape, rather than from `centreline.csv`
/// (rounded to 10⁻⁶ cm, and not straight for a run that starts knotted).
#[derive(Clone, Debug, PartialEq)]
pub struct RunField {
    /// The run directory.
    pub directory: PathBuf,
    /// Time of each frame (s).
    pub times: Vec<f64>,
    /// Phase of each frame (`metrics.csv`'s `phase`).
    pub phases: Vec<String>,
    /// `knot_core_start_cm` of each frame: the knotted core's head-ward end (cm from the head
    /// body's centre), the knot position the slide's speed is measured by.
    pub knot_cm: Vec<Option<f64>>,
    /// Kind of each DOF, in tree order (the columns of `thigmo_force.npy`).
    pub kinds: Vec<DofKind>,
    /// Arc length of each DOF (cm).
    pub arcs_cm: Vec<f64>,
    /// The body length L (cm).
    pub length_cm: f64,
    /// The field, frames × DOFs, row-major (dyn·cm).
    pub values: Vec<f64>,
}

impl RunField {
    /// Reads the run directory `directory`. Frames are those both `metrics.csv` and
    /// `thigmo_force.npy` hold (a killed run may have one more row in one of them).
    pub fn read(directory: &Path) -> Result<Self, ModesError> {
        if !directory.is_dir() {
            let what = if directory.exists() { "not a directory" } else { "does not exist" };
            return Err(ModesError::NoRunDirectory { path: directory.into(), what: what.into() });
        }
        let metrics = Metrics::read(&directory.join("metrics.csv"))?;
        let npy_path = directory.join("thigmo_force.npy");
        let force = read_npy(&npy_path)?;
        let scenario_path = directory.join("scenario.ron");
        let scenario_error = |source: Box<dyn std::error::Error + Send + Sync>| {
            ModesError::Scenario { path: scenario_path.clone(), source }
        };
        let loaded = LoadedScenario::load(&scenario_path).map_err(|e| scenario_error(e.into()))?;
        let model = loaded.body.to_model().map_err(|e| scenario_error(e.into()))?;
        let arcs_cm = hagfish_sim::rest_dof_arc_lengths(&model);
        let labels = hagfish_sim::dof_labels(&model);
        let kinds = labels.iter().map(|l| DofKind::from_axis(l.axis)).collect::<Option<Vec<_>>>();
        let kinds =
            kinds.ok_or_else(|| scenario_error("a DOF about an axis other than X, Y, Z".into()))?;
        if force.columns != kinds.len() {
            return Err(ModesError::Mismatch {
                path: npy_path,
                what: format!("{} columns, but the body has {} DOFs", force.columns, kinds.len()),
            });
        }
        let frames = force.rows.min(metrics.time.len());
        let mut values = force.values;
        values.truncate(frames * force.columns);
        Ok(Self {
            directory: directory.into(),
            times: metrics.time[..frames].to_vec(),
            phases: metrics.phase[..frames].to_vec(),
            knot_cm: metrics.knot_core_start[..frames].to_vec(),
            kinds,
            arcs_cm,
            length_cm: loaded.body.length_cm(),
            values,
        })
    }

    /// The field of the frames of `phase` (all frames with a non-zero selected field when
    /// `None`) and the DOFs `kinds` selects, in tree order.
    pub fn select(&self, phase: Option<&str>, kinds: KindSelection) -> Result<Field, ModesError> {
        let dofs: Vec<usize> =
            (0..self.kinds.len()).filter(|&d| kinds.includes(self.kinds[d])).collect();
        let width = self.kinds.len();
        let row = |f: usize| dofs.iter().map(move |&d| self.values[f * width + d]);
        let frames: Vec<usize> = (0..self.times.len())
            .filter(|&f| match phase {
                Some(name) => self.phases[f] == name,
                None => row(f).any(|v| v != 0.0),
            })
            .collect();
        let label = format!("phase {}, {kinds}", phase.unwrap_or("(thigmotaxis)"));
        if frames.is_empty() {
            if phase.is_none() {
                return Err(ModesError::ZeroField { what: label });
            }
            let mut available = self.phases.clone();
            available.dedup();
            return Err(ModesError::NoFrames {
                phase: phase.unwrap_or_default().into(),
                available: available.join(", "),
            });
        }
        Field::new(
            label,
            frames.iter().map(|&f| self.times[f]).collect(),
            dofs.iter().map(|&d| self.arcs_cm[d]).collect(),
            self.length_cm,
            frames.iter().map(|&f| self.knot_cm[f]).collect(),
            frames.iter().flat_map(|&f| row(f)).collect(),
        )
    }
}
