//! The minimal dynamic state: time, reduced coordinates and their rates.

use crate::error::TreeError;
use crate::model::Model;

/// The state of a tree: `t` (s), joint angles `q` (rad) and rates `q̇` (rad/s). Everything else
/// is derived from it (see [`crate::Data`]).
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// Simulation time (s).
    pub t: f64,
    /// Reduced coordinates (rad), indexed by DOF.
    pub q: Vec<f64>,
    /// Reduced velocities (rad/s), indexed by DOF.
    pub qdot: Vec<f64>,
}

impl State {
    /// The rest state of `model`: `t = 0`, `q = q_rest`, `q̇ = 0`.
    pub fn rest(model: &Model) -> Self {
        Self {
            t: 0.0,
            q: model.dofs().iter().map(|d| d.rest).collect(),
            qdot: vec![0.0; model.dof_count()],
        }
    }

    /// Checks the lengths of `q` and `q̇` against `model` and that every entry is finite.
    pub fn validate(&self, model: &Model) -> Result<(), TreeError> {
        model.check_dof_vector("q", self.q.len())?;
        model.check_dof_vector("qdot", self.qdot.len())?;
        for (what, v) in [("q", &self.q), ("qdot", &self.qdot)] {
            if let Some(dof) = v.iter().position(|x| !x.is_finite()) {
                return Err(TreeError::NonFinite { time: self.t, what, dof });
            }
        }
        Ok(())
    }
}
