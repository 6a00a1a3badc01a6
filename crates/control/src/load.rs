//! A load on the tail end: a force of given magnitude along a fixed world direction or along
//! the tail's tangent, ramped up linearly, for pulling a rod or a hagfish (the cantilever and
//! knot-under-tension checks of `docs/validation.md`).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, PointForce};
use crate::until::Until;

/// Which way the load pulls.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum LoadDirection {
    /// A fixed world direction (normalised; a dead load), e.g. `Fixed((0.0, 1.0, 0.0))`.
    Fixed((f64, f64, f64)),
    /// Along the last body's axis, away from the head (a follower load).
    TailTangent,
}

/// A load phase: from its start, a force of `force_dyn · min(1, t/ramp_s)` on the tail end (the
/// far end of the last body). The load stays on after the phase ends, as a weight hung on
/// the tail would, until a later load phase replaces it (`force_dyn: 0.0` removes it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadPhase {
    /// Magnitude once ramped (dyn), ≥ 0.
    pub force_dyn: f64,
    /// Direction.
    pub direction: LoadDirection,
    /// Time to ramp the magnitude up from 0 (s), ≥ 0 (0: at once).
    #[serde(default)]
    pub ramp_s: f64,
    /// When the phase ends, e.g. `(seconds: 20.0, hold_s: 0.5, when: [(KineticEnergy, Below,
    /// Erg(1e-9))])`: settled.
    pub until: Until,
}

impl LoadPhase {
    /// The force (dyn) at time `t` of a load applied since `started_at`, on a tail whose axis
    /// points along `tail_axis`.
    pub fn force(&self, t: f64, started_at: f64, tail_axis: DVec3) -> DVec3 {
        let ramp =
            if self.ramp_s > 0.0 { ((t - started_at) / self.ramp_s).clamp(0.0, 1.0) } else { 1.0 };
        let direction = match self.direction {
            LoadDirection::Fixed((x, y, z)) => DVec3::new(x, y, z).normalize_or_zero(),
            LoadDirection::TailTangent => tail_axis,
        };
        direction * (self.force_dyn * ramp)
    }

    /// Applies the load at the tail end for the step of `context`.
    pub fn actuate(&self, started_at: f64, context: &ControlContext<'_>, out: &mut Actuation) {
        let (tail, end, rotation) = context.tail_end();
        let force = self.force(context.state.t, started_at, rotation.col(0));
        out.forces.push(PointForce { body: tail, point: end, force });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_force_ramps_up_and_then_stays() {
        let load = LoadPhase {
            force_dyn: 2.0,
            direction: LoadDirection::Fixed((0.0, 3.0, 0.0)),
            ramp_s: 1.0,
            until: Until::default(),
        };
        assert_eq!(load.force(10.0, 10.0, DVec3::X), DVec3::ZERO);
        assert_eq!(load.force(10.5, 10.0, DVec3::X), DVec3::new(0.0, 1.0, 0.0));
        assert_eq!(load.force(30.0, 10.0, DVec3::X), DVec3::new(0.0, 2.0, 0.0));
        let follower = LoadPhase { direction: LoadDirection::TailTangent, ramp_s: 0.0, ..load };
        assert_eq!(follower.force(10.0, 10.0, DVec3::Z), DVec3::new(0.0, 0.0, 2.0));
    }
}
