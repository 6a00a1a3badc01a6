//! A pull at prescribed speed: the tail end gripped (clamped in position and orientation) and
//! moved at a constant velocity, the way a testing machine pulls a rod (Choi, Tong, Jawed &
//! Joo 2021 clamp both ends of their rod and pull them apart at 3–9 mm/s). The force the grip
//! needs is the pull force, read off its rows' multipliers (docs/physics.md, "Pulls at prescribed speed (grip)").
//!
//! The grip's target at time t of a pull that started at t₀ with the tail end at x₀ and the
//! tail's orientation R₀ is `x*(t) = x₀ + v τ` with τ = min(t, t₁) − t₀ (t₁ when the phase
//! ended: the grip then holds the end where the pull left it, until a later pull takes over)
//! and R₀; with a ramp of r seconds the speed rises linearly and x*(t) = x₀ + v τ²/(2r) for
//! τ < r, x₀ + v (τ − r/2) after.

use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

use crate::controller::{ControlContext, Grip};
use crate::until::Until;

/// A pull phase: from its start, the tail end moves at `speed_cm_per_s` along the fixed world
/// `direction`, its orientation held; after the phase the grip holds it still.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PullPhase {
    /// Speed of the tail end (cm/s), ≥ 0.
    pub speed_cm_per_s: f64,
    /// World direction of the pull (normalised when used), e.g. `(1.0, 0.0, 0.0)`.
    pub direction: (f64, f64, f64),
    /// Time over which the speed rises linearly from 0 (s), ≥ 0 (0: at once, as a clamp
    /// that starts at full speed; its first step then takes the jerk).
    #[serde(default)]
    pub ramp_s: f64,
    /// When the phase ends, e.g. `(seconds: 60.0)`.
    pub until: Until,
}

impl PullPhase {
    /// The tail end's velocity (cm/s): `speed · direction/|direction|`.
    pub fn velocity(&self) -> DVec3 {
        let (x, y, z) = self.direction;
        DVec3::new(x, y, z).normalize_or_zero() * self.speed_cm_per_s
    }
}

/// Where a pull started and, once its phase is over, when it stopped: the controller state a
/// checkpoint keeps so that a resumed run grips the same trajectory.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PullAnchor {
    /// Index of the pull's phase.
    pub phase: usize,
    /// When the pull started (s).
    pub since_s: f64,
    /// When its phase ended (s), or `None` while it runs.
    #[serde(default)]
    pub stopped_s: Option<f64>,
    /// The tail end at the start (cm).
    pub end_cm: [f64; 3],
    /// The tail's orientation at the start (a unit quaternion x, y, z, w).
    pub rotation: [f64; 4],
    /// The pull's velocity once ramped up (cm/s).
    pub velocity_cm_per_s: [f64; 3],
    /// The ramp's duration (s).
    #[serde(default)]
    pub ramp_s: f64,
}

impl PullAnchor {
    /// The anchor of `pull`, phase `phase`, starting now with the tail as `context` sees it.
    pub fn start(pull: &PullPhase, phase: usize, context: &ControlContext<'_>) -> Self {
        let (_, end, rotation) = context.tail_end();
        Self {
            phase,
            since_s: context.state.t,
            stopped_s: None,
            end_cm: end.to_array(),
            rotation: DQuat::from_mat3(&rotation).to_array(),
            velocity_cm_per_s: pull.velocity().to_array(),
            ramp_s: pull.ramp_s,
        }
    }

    /// The distance pulled by time `t` over the speed (s), τ = min(t, t₁) − t₀ into the
    /// pull: `τ²/(2r)` while the speed ramps up over r, then `τ − r/2`.
    fn pulled_s(&self, t: f64) -> f64 {
        let tau = (self.stopped_s.map_or(t, |stopped| t.min(stopped)) - self.since_s).max(0.0);
        let ramp = self.ramp_s;
        if tau < ramp { tau * tau / (2.0 * ramp) } else { tau - 0.5 * ramp }
    }

    /// The grip's target end at time `t`: x₀ + v·(the distance pulled over the speed) (cm).
    pub fn target(&self, t: f64) -> DVec3 {
        DVec3::from_array(self.end_cm)
            + DVec3::from_array(self.velocity_cm_per_s) * self.pulled_s(t)
    }

    /// The target's velocity at time `t` (cm/s): v·min(1, τ/r) while the pull runs, zero
    /// after its phase.
    pub fn velocity(&self, t: f64) -> DVec3 {
        if self.stopped_s.is_some_and(|stopped| t >= stopped) {
            return DVec3::ZERO;
        }
        let tau = (t - self.since_s).max(0.0);
        let ramp = if self.ramp_s > 0.0 { (tau / self.ramp_s).min(1.0) } else { 1.0 };
        DVec3::from_array(self.velocity_cm_per_s) * ramp
    }

    /// The grip for the step of `context`: the tail end, its target position and velocity,
    /// and the rotation vector that turns the tail's orientation back to R₀.
    pub fn grip(&self, context: &ControlContext<'_>) -> Grip {
        let t = context.state.t;
        let (body, end, rotation) = context.tail_end();
        let held = DQuat::from_array(self.rotation);
        let turn = (held * DQuat::from_mat3(&rotation).inverse()).normalize();
        // The shorter way round: q and −q are the same rotation.
        let turn = if turn.w < 0.0 { -turn } else { turn };
        Grip {
            body,
            point: end,
            target: self.target(t),
            velocity: self.velocity(t),
            rotation_error: turn.to_scaled_axis(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn anchor() -> PullAnchor {
        PullAnchor {
            phase: 1,
            since_s: 2.0,
            stopped_s: None,
            end_cm: [10.0, 0.0, 0.0],
            rotation: DQuat::IDENTITY.to_array(),
            velocity_cm_per_s: [0.5, 0.0, 0.0],
            ramp_s: 0.0,
        }
    }

    #[test]
    fn the_target_moves_at_the_pull_speed_and_stops_with_the_phase() {
        let mut anchor = anchor();
        assert_eq!(anchor.target(2.0), DVec3::new(10.0, 0.0, 0.0));
        assert_eq!(anchor.target(6.0), DVec3::new(12.0, 0.0, 0.0));
        anchor.stopped_s = Some(4.0);
        assert_eq!(anchor.target(6.0), DVec3::new(11.0, 0.0, 0.0));
        assert_eq!(anchor.velocity(6.0), DVec3::ZERO);
    }

    #[test]
    fn a_ramped_pull_speeds_up_linearly_and_then_lags_half_its_ramp() {
        let anchor = PullAnchor { ramp_s: 2.0, ..anchor() };
        assert_eq!(anchor.velocity(3.0), DVec3::new(0.25, 0.0, 0.0));
        assert_eq!(anchor.target(3.0), DVec3::new(10.0 + 0.5 * 0.25, 0.0, 0.0));
        assert_eq!(anchor.velocity(5.0), DVec3::new(0.5, 0.0, 0.0));
        // After the ramp: x₀ + v(τ − r/2), τ = 3 s.
        assert_eq!(anchor.target(5.0), DVec3::new(10.0 + 0.5 * 2.0, 0.0, 0.0));
    }

    #[test]
    fn the_velocity_is_the_speed_along_the_normalised_direction() {
        let pull = PullPhase {
            speed_cm_per_s: 0.6,
            direction: (0.0, 3.0, 4.0),
            ramp_s: 0.0,
            until: Until::default(),
        };
        assert!((pull.velocity() - DVec3::new(0.0, 0.36, 0.48)).length() < 1e-15);
    }
}
