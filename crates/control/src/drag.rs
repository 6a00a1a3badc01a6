//! Water drag on the body: each body's centre feels `F = −(c₁ + c₂|v|) ℓ_i 2r_i v`, a linear
//! (viscous) plus a quadratic (form) drag per unit projected area, linearised about the
//! current speed and applied as an implicit damper so it can never destabilise the step.
//!
//! With water's density ρ = 1 g/cm³ and a drag coefficient C_d ≈ 1, the quadratic
//! coefficient is ½ρC_d ≈ 0.5 g/cm³. The drag is isotropic (a cylinder moving along its axis
//! feels less; that refinement is left out).

use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, Controller, PointDamper};

/// Water drag parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WaterDrag {
    /// Linear coefficient c₁ per projected area (dyn·s/cm³): force c₁·A·v.
    pub linear_dyn_s_per_cm3: f64,
    /// Quadratic coefficient c₂ per projected area (g/cm³): force c₂·A·|v|·v (½ρC_d).
    pub quadratic_g_per_cm3: f64,
}

impl Default for WaterDrag {
    fn default() -> Self {
        Self { linear_dyn_s_per_cm3: 0.0, quadratic_g_per_cm3: 0.5 }
    }
}

impl Controller for WaterDrag {
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        for (body, b) in context.model.bodies().iter().enumerate() {
            let area = 2.0 * b.radius * b.length;
            let speed = context.centre_velocity(body).length();
            let coefficient = area * (self.linear_dyn_s_per_cm3 + self.quadratic_g_per_cm3 * speed);
            if coefficient > 0.0 {
                out.dampers.push(PointDamper { body, point: context.centre(body), coefficient });
            }
        }
    }
}
