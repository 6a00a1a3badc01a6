//! The worst values of the steps between two recorded frames: penetrations and limit excess.

use serde::{Deserialize, Serialize};

use crate::report::StepReport;

/// Worst values over the steps between two frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct IntervalMaxima {
    /// Deepest self penetration (cm).
    pub self_penetration: f64,
    /// Deepest self penetration relative to the local radius.
    pub self_penetration_relative: f64,
    /// Deepest compression of the skins at a self contact, fraction of their thickness.
    #[serde(default)]
    pub skin_compression: f64,
    /// Deepest wall penetration (cm).
    pub wall_penetration: f64,
    /// Largest excess of a joint over a limit (rad).
    pub limit_excess: f64,
}

impl IntervalMaxima {
    /// Takes the maxima of `self` and the step's.
    pub fn include(&mut self, step: &StepReport, limit_excess: f64) {
        self.self_penetration = self.self_penetration.max(step.max_self_penetration);
        self.self_penetration_relative =
            self.self_penetration_relative.max(step.max_self_penetration_relative);
        self.skin_compression = self.skin_compression.max(step.max_skin_compression);
        self.wall_penetration = self.wall_penetration.max(step.max_wall_penetration);
        self.limit_excess = self.limit_excess.max(limit_excess);
    }

    /// The maxima of both.
    pub fn merge(&mut self, other: &IntervalMaxima) {
        self.self_penetration = self.self_penetration.max(other.self_penetration);
        self.self_penetration_relative =
            self.self_penetration_relative.max(other.self_penetration_relative);
        self.skin_compression = self.skin_compression.max(other.skin_compression);
        self.wall_penetration = self.wall_penetration.max(other.wall_penetration);
        self.limit_excess = self.limit_excess.max(other.limit_excess);
    }
}
