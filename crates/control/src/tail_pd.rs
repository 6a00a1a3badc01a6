//! A PD pull on the tail body toward a moving target, with the derivative part and the
//! linearised proportional part implicit.
//!
//! `F = k_p (x* − x¹) + k_d (v* − ẋ¹)` at the tail centre, evaluated at the new state of the
//! step: with `x¹ ≈ x⁰ + h ẋ¹` this is the explicit force `k_p (x* − x⁰) + k_d v*` plus the
//! implicit damper `(k_d + h k_p)`. An explicit `k_d` on the 0.54 g tail body would diverge
//! once `h k_d / m ≥ 2` (the peer engine's experience); the implicit form is stable for any
//! gain. The explicit part is capped at `max_force`.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, PointDamper, PointForce};

/// Gains and cap of the tail pull.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TailGains {
    /// Proportional gain k_p (dyn/cm).
    pub kp_dyn_per_cm: f64,
    /// Derivative gain k_d (dyn·s/cm).
    pub kd_dyn_s_per_cm: f64,
    /// Cap on the explicit force (dyn).
    pub max_force_dyn: f64,
}

impl Default for TailGains {
    fn default() -> Self {
        Self { kp_dyn_per_cm: 200.0, kd_dyn_s_per_cm: 20.0, max_force_dyn: 2000.0 }
    }
}

impl TailGains {
    /// Pulls the last body toward `target` (cm) moving at `target_velocity` (cm/s).
    pub fn pull(
        &self,
        context: &ControlContext<'_>,
        target: DVec3,
        target_velocity: DVec3,
        out: &mut Actuation,
    ) {
        let tail = context.model.body_count() - 1;
        let x = context.centre(tail);
        let explicit = (target - x) * self.kp_dyn_per_cm + target_velocity * self.kd_dyn_s_per_cm;
        let force = explicit.clamp_length_max(self.max_force_dyn);
        out.forces.push(PointForce { body: tail, point: x, force });
        let coefficient = self.kd_dyn_s_per_cm + context.time_step * self.kp_dyn_per_cm;
        out.dampers.push(PointDamper { body: tail, point: x, coefficient });
    }
}
