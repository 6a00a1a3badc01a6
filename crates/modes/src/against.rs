//! One run's modes against another's (`hagfish modes RUN_DIR --against OTHER`): the principal
//! angles between the two runs' first k mode shapes on a common s/L grid, and the fraction of
//! the run's field energy that the other run's first k modes capture, for each k.

use std::path::{Path, PathBuf};

use crate::angles::{captured_energy, principal_angles, resample, uniform_grid};
use crate::error::ModesError;
use crate::output::{Decomposition, MODES_DIR};

/// The points of the common s/L grid (0 to 1) the two bases are resampled on for their
/// principal angles: finer than the finest body of the family (300 bodies).
pub const GRID_POINTS: usize = 1001;

/// The file of the comparison in `RUN_DIR/modes/`.
pub const AGAINST_FILE: &str = "against.json";

/// One selection of a run compared with the same selection of another run.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Comparison {
    /// The DOF kind (one kind: its DOFs have distinct arc lengths).
    pub kind: String,
    /// The frames × DOFs of the run's field.
    pub size: [usize; 2],
    /// The frames × DOFs of the other run's field.
    pub other_size: [usize; 2],
    /// The principal angles (degrees, increasing) between the spans of the two runs' first k
    /// shapes, k = the modes compared (fewer if either field has fewer modes).
    pub principal_angles_deg: Vec<f64>,
    /// The run's own cumulative energy fractions of its first 1, 2, … k modes: what its own
    /// basis captures, the most any k-dimensional basis can.
    pub own_cumulative: Vec<f64>,
    /// The fraction of the run's field energy in the span of the other run's first 1, 2, … k
    /// shapes (resampled at the run's s/L).
    pub captured_by_other: Vec<f64>,
}

impl Comparison {
    /// `run`'s decomposition against `other`'s over their first `modes` modes. Both must be of
    /// one DOF kind, the same one.
    pub fn of(
        run: &Decomposition,
        other: &Decomposition,
        modes: usize,
    ) -> Result<Self, ModesError> {
        if run.kind != other.kind {
            return Err(ModesError::Incompatible(format!(
                "the selections differ: {} against {}",
                run.kind, other.kind
            )));
        }
        for d in [run, other] {
            if d.field.arcs_cm.windows(2).any(|w| w[1] <= w[0]) {
                return Err(ModesError::Incompatible(format!(
                    "{}: its DOFs share arc lengths; compare one DOF kind (bend-y, bend-z or \
                     twist)",
                    d.field.label
                )));
            }
        }
        if modes == 0 {
            return Err(ModesError::Incompatible("compare at least one mode".into()));
        }
        let k = modes.min(run.pod.modes()).min(other.pod.modes());
        let (run_l, other_l) = (run.field.arcs_l(), other.field.arcs_l());
        let grid = uniform_grid(GRID_POINTS);
        let angles = principal_angles(
            &resample(&run_l, &run.pod.shapes[..k], &grid)?,
            &resample(&other_l, &other.pod.shapes[..k], &grid)?,
        )?;
        let captured_by_other = (1..=k)
            .map(|j| captured_energy(&run.field, &other_l, &other.pod.shapes[..j]))
            .collect::<Result<Vec<_>, _>>()?;
        let size = |d: &Decomposition| [d.field.frames(), d.field.dofs()];
        Ok(Self {
            kind: run.kind.name().into(),
            size: size(run),
            other_size: size(other),
            principal_angles_deg: angles.iter().map(|a| a.to_degrees()).collect(),
            own_cumulative: run.pod.cumulative_fractions()[..k].to_vec(),
            captured_by_other,
        })
    }
}

/// Writes `comparisons` of the run at `directory` against the run at `other` into
/// `directory/modes/against.json`; returns its path.
pub fn write_against(
    directory: &Path,
    other: &Path,
    phase: Option<&str>,
    comparisons: &[Comparison],
) -> Result<PathBuf, ModesError> {
    let out = directory.join(MODES_DIR);
    std::fs::create_dir_all(&out)
        .map_err(|source| ModesError::Write { path: out.clone(), source })?;
    let json = serde_json::json!({
        "run": directory.display().to_string(),
        "other": other.display().to_string(),
        "phase": phase,
        "mean_removed": false,
        "grid_points": GRID_POINTS,
        "selections": comparisons,
    });
    let path = out.join(AGAINST_FILE);
    let text = serde_json::to_string_pretty(&json).unwrap_or_default();
    hagfish_run::replace_file(&path, text.as_bytes())?;
    Ok(path)
}
