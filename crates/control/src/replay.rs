//! Open-loop replay: a recorded generalized force field applied as joint torques, without
//! contact feedback (`docs/physics.md`, "Open-loop replay").

use std::path::PathBuf;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

/// A thigmotaxis phase's replay (`parameters.replay: Some((file: "…/replay_all_k8.csv"))`):
/// instead of its rows the phase applies, at time τ since the phase began, the field of the
/// file at τ as joint torques τ_ext (dyn·cm per DOF). The tail pull stays. The file is
/// written by `hagfish modes RUN_DIR --phase P --replay K`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Replay {
    /// The CSV file (`time_s` since the recorded phase's first frame, then one column per
    /// DOF in tree order); relative to the scenario file's directory.
    pub file: PathBuf,
    /// The field read from `file`; `None` until the scenario is loaded (no torque then).
    #[serde(skip)]
    pub field: Option<Arc<ReplayField>>,
}

impl PartialEq for Replay {
    /// Two replays are equal when they name the same file.
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file
    }
}

/// A field F(τ) sampled at increasing times: frames × DOFs, row-major (dyn·cm).
#[derive(Clone, Debug, PartialEq)]
pub struct ReplayField {
    times: Vec<f64>,
    dofs: usize,
    values: Vec<f64>,
}

impl ReplayField {
    /// The field of `times` (strictly increasing, finite) × `dofs` `values` (finite); an
    /// error says what does not fit.
    pub fn new(times: Vec<f64>, dofs: usize, values: Vec<f64>) -> Result<Self, String> {
        if times.is_empty() || values.len() != times.len() * dofs {
            return Err(format!("{} values for {} times × {dofs} DOFs", values.len(), times.len()));
        }
        if !times.windows(2).all(|w| w[0] < w[1]) || !times.iter().all(|t| t.is_finite()) {
            return Err("the times are not finite and strictly increasing".into());
        }
        if !values.iter().all(|v| v.is_finite()) {
            return Err("a value is not finite".into());
        }
        Ok(Self { times, dofs, values })
    }

    /// The number of DOFs.
    pub fn dofs(&self) -> usize {
        self.dofs
    }

    /// Writes F(τ) into `out` (resized to the DOFs): linear between the two samples around
    /// τ, zero before the first sample and after the last (the replay ends with its record).
    pub fn sample(&self, tau: f64, out: &mut Vec<f64>) {
        out.clear();
        out.resize(self.dofs, 0.0);
        let (first, last) = (self.times[0], self.times[self.times.len() - 1]);
        if !(first..=last).contains(&tau) {
            return;
        }
        let next = self.times.partition_point(|t| *t <= tau).min(self.times.len() - 1);
        let before = next.saturating_sub(1);
        let span = self.times[next] - self.times[before];
        let w = if span > 0.0 { (tau - self.times[before]) / span } else { 0.0 };
        let (a, b) = (before * self.dofs, next * self.dofs);
        for (d, o) in out.iter_mut().enumerate() {
            *o = (1.0 - w) * self.values[a + d] + w * self.values[b + d];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_field_is_linear_between_samples_and_zero_outside_them() -> Result<(), String> {
        let field = ReplayField::new(vec![0.0, 0.1, 0.3], 2, vec![0.0, 1.0, 2.0, 3.0, 4.0, 7.0])?;
        let mut out = Vec::new();
        field.sample(0.05, &mut out);
        assert_eq!(out, [1.0, 2.0]);
        field.sample(0.2, &mut out);
        assert!((out[0] - 3.0).abs() < 1e-12 && (out[1] - 5.0).abs() < 1e-12, "{out:?}");
        field.sample(0.3, &mut out);
        assert_eq!(out, [4.0, 7.0]);
        field.sample(0.0, &mut out);
        assert_eq!(out, [0.0, 1.0]);
        for outside in [-0.01, 0.31] {
            field.sample(outside, &mut out);
            assert_eq!(out, [0.0, 0.0]);
        }
        assert!(ReplayField::new(vec![0.0, 0.0], 1, vec![1.0, 2.0]).is_err());
        assert!(ReplayField::new(vec![0.0], 2, vec![1.0]).is_err());
        assert!(ReplayField::new(vec![0.0], 1, vec![f64::NAN]).is_err());
        Ok(())
    }
}
