//! Step acceptance: a step's result is kept only if it is physically valid — self and wall
//! penetration and joint-limit excess within bounds, an inexact velocity solve with a small
//! residual (`docs/physics.md`). The bounds are scenario options; a rejected step is retried
//! by the runner, with its contacts at the chain's resolution and then with substeps
//! (`run.rs`).

use serde::{Deserialize, Serialize};

use crate::error::SimError;

/// When the end of a step is physically valid (`docs/physics.md`, step acceptance): a step
/// whose result exceeds a bound is rejected, and the runner retries it with substeps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StepAcceptance {
    /// Deepest self penetration allowed at the end of a step, as a fraction of the local
    /// radius `(r_a + r_b)/2`. Default 0.1 (the shipped scenarios stay below 0.01).
    pub max_self_penetration_relative: f64,
    /// Deepest wall penetration allowed, as a fraction of the penetrating body's radius.
    /// Default 0.1.
    pub max_wall_penetration_relative: f64,
    /// Largest excess of a joint over its limits allowed (degrees). Default 2.
    pub max_limit_excess_deg: f64,
    /// Largest relative KKT residual accepted from a `SolvedInexact` velocity solve (the
    /// solver's `worst_relative`; `Solved` means below its acceptance, 1e-9). Default 1e-4.
    pub max_inexact_residual: f64,
    /// Largest rotation rate |q̇ᵢ| of a joint allowed at the end of a step (rad/s; translations
    /// are not bounded). Default 100: the valid runs measured stay below 30 rad/s (ES103
    /// family, drag down to ×0.1), while an unstable chain passes 500 rad/s within 0.2 s
    /// without any contact or limit to reject it.
    pub max_joint_rate_rad_s: f64,
    /// Largest distance of a pull's gripped end from its target allowed at the end of a step
    /// (cm), or `None` (the default) for no bound. The grip's velocity rows are met exactly,
    /// but the position update q ← q + h q̇ leaves the end off its line by an error that grows
    /// with h² and the square of the joints' rates; a pull past a knot's tightest fails once
    /// it reaches tenths of a millimetre a step (docs/validation.md, "Loop inversion").
    pub max_grip_error_cm: Option<f64>,
    /// How many times a rejected step is halved before the run stops as diverged: h/2, h/4,
    /// …, h/2^k (default 4: down to h/16).
    pub max_halvings: u32,
    /// Whether a rejected step is first retried whole with its self contacts at the chain's
    /// resolution ([`crate::StepOptions::resolved_cluster_radius`]; default true). Changes
    /// nothing on chains whose contacts are already that fine (ES103 and coarser).
    pub resolve_contacts: bool,
}

impl Default for StepAcceptance {
    fn default() -> Self {
        Self {
            max_self_penetration_relative: 0.1,
            max_wall_penetration_relative: 0.1,
            max_limit_excess_deg: 2.0,
            max_inexact_residual: 1e-4,
            max_joint_rate_rad_s: 100.0,
            max_grip_error_cm: None,
            max_halvings: 4,
            resolve_contacts: true,
        }
    }
}

impl StepAcceptance {
    /// Checks every bound (finite and > 0; at most 20 halvings).
    pub fn validate(&self) -> Result<(), SimError> {
        let bounds = [
            ("max_self_penetration_relative", self.max_self_penetration_relative),
            ("max_wall_penetration_relative", self.max_wall_penetration_relative),
            ("max_limit_excess_deg", self.max_limit_excess_deg),
            ("max_inexact_residual", self.max_inexact_residual),
            ("max_joint_rate_rad_s", self.max_joint_rate_rad_s),
        ];
        let grip = self.max_grip_error_cm.map(|bound| ("max_grip_error_cm", bound));
        for (name, value) in bounds.into_iter().chain(grip) {
            if !(value.is_finite() && value > 0.0) {
                return Err(SimError::InvalidOption { name, value, expected: "finite and > 0" });
            }
        }
        if self.max_halvings > MAX_HALVINGS {
            let value = f64::from(self.max_halvings);
            return Err(SimError::InvalidOption {
                name: "max_halvings", value, expected: "≤ 20"
            });
        }
        Ok(())
    }
}

/// The most halvings of a rejected step (h/2²⁰ ≈ 1e-6 h).
const MAX_HALVINGS: u32 = 20;

/// Why a step's result was rejected: the measured value and the bound it exceeds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rejection {
    /// Self penetration at the end of the step, relative to the local radius.
    SelfPenetration {
        /// Measured (fraction of the local radius).
        relative: f64,
        /// [`StepAcceptance::max_self_penetration_relative`].
        bound: f64,
    },
    /// Wall penetration at the end of the step, relative to the body's radius.
    WallPenetration {
        /// Measured (fraction of the radius).
        relative: f64,
        /// [`StepAcceptance::max_wall_penetration_relative`].
        bound: f64,
    },
    /// A joint beyond its limit at the end of the step.
    LimitExcess {
        /// Measured (degrees).
        degrees: f64,
        /// [`StepAcceptance::max_limit_excess_deg`].
        bound: f64,
    },
    /// A joint turning faster than the bound at the end of the step.
    JointRate {
        /// Measured (rad/s).
        rad_s: f64,
        /// [`StepAcceptance::max_joint_rate_rad_s`].
        bound: f64,
    },
    /// A pull's gripped end too far from its target at the end of the step.
    GripError {
        /// Measured (cm).
        cm: f64,
        /// [`StepAcceptance::max_grip_error_cm`].
        bound: f64,
    },
    /// A `SolvedInexact` velocity solve whose residual is too large.
    InexactSolve {
        /// The solve's worst relative KKT residual.
        residual: f64,
        /// [`StepAcceptance::max_inexact_residual`].
        bound: f64,
    },
}

impl std::fmt::Display for Rejection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Rejection::SelfPenetration { relative, bound } => write!(
                f,
                "self penetration {:.1} % of the local radius (bound {:.1} %)",
                100.0 * relative,
                100.0 * bound
            ),
            Rejection::WallPenetration { relative, bound } => write!(
                f,
                "wall penetration {:.1} % of the radius (bound {:.1} %)",
                100.0 * relative,
                100.0 * bound
            ),
            Rejection::LimitExcess { degrees, bound } => {
                write!(f, "a joint {degrees:.3}° beyond its limit (bound {bound}°)")
            }
            Rejection::JointRate { rad_s, bound } => {
                write!(f, "a joint turning at {rad_s:.1} rad/s (bound {bound} rad/s)")
            }
            Rejection::GripError { cm, bound } => {
                write!(f, "the grip {cm:.4} cm from its target (bound {bound} cm)")
            }
            Rejection::InexactSolve { residual, bound } => {
                write!(f, "inexact velocity solve, residual {residual:.2e} (bound {bound:.0e})")
            }
        }
    }
}

/// What the end of a step measures for its acceptance.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EndOfStep {
    /// Deepest self penetration relative to the local radius.
    pub self_penetration_relative: f64,
    /// Deepest wall penetration relative to the body's radius.
    pub wall_penetration_relative: f64,
    /// Largest excess of a joint over its limits (rad).
    pub limit_excess: f64,
    /// Largest rotation rate |q̇ᵢ| of a joint (rad/s; NaN if any rate is not finite).
    pub joint_rate: f64,
    /// How far a pull's gripped end is from its target (cm; 0 without a grip).
    pub grip_error_cm: f64,
    /// The worst relative KKT residual of the velocity solve, if it was `SolvedInexact`.
    pub inexact_residual: Option<f64>,
}

impl StepAcceptance {
    /// The first bound `end` exceeds, or `None` when the step is accepted.
    pub fn judge(&self, end: &EndOfStep) -> Option<Rejection> {
        let degrees = end.limit_excess.to_degrees();
        if end.self_penetration_relative > self.max_self_penetration_relative {
            Some(Rejection::SelfPenetration {
                relative: end.self_penetration_relative,
                bound: self.max_self_penetration_relative,
            })
        } else if end.wall_penetration_relative > self.max_wall_penetration_relative {
            Some(Rejection::WallPenetration {
                relative: end.wall_penetration_relative,
                bound: self.max_wall_penetration_relative,
            })
        } else if degrees > self.max_limit_excess_deg || !degrees.is_finite() {
            Some(Rejection::LimitExcess { degrees, bound: self.max_limit_excess_deg })
        } else if end.joint_rate > self.max_joint_rate_rad_s || end.joint_rate.is_nan() {
            Some(Rejection::JointRate { rad_s: end.joint_rate, bound: self.max_joint_rate_rad_s })
        } else if let Some(bound) =
            self.max_grip_error_cm.filter(|&b| end.grip_error_cm > b || end.grip_error_cm.is_nan())
        {
            Some(Rejection::GripError { cm: end.grip_error_cm, bound })
        } else {
            end.inexact_residual.filter(|r| r.is_nan() || *r > self.max_inexact_residual).map(
                |residual| Rejection::InexactSolve { residual, bound: self.max_inexact_residual },
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_bound_rejects_just_above_it_and_accepts_at_it() {
        let bounds = StepAcceptance::default();
        let at = EndOfStep {
            self_penetration_relative: bounds.max_self_penetration_relative,
            wall_penetration_relative: bounds.max_wall_penetration_relative,
            limit_excess: bounds.max_limit_excess_deg.to_radians() * (1.0 - 1e-12),
            joint_rate: bounds.max_joint_rate_rad_s,
            grip_error_cm: 0.01,
            inexact_residual: Some(bounds.max_inexact_residual),
        };
        assert_eq!(bounds.judge(&at), None, "the grip is not bounded by default");
        let bounds = StepAcceptance { max_grip_error_cm: Some(0.01), ..bounds };
        assert_eq!(bounds.judge(&at), None);
        let above = |change: fn(&mut EndOfStep)| {
            let mut end = at;
            change(&mut end);
            bounds.judge(&end)
        };
        assert!(matches!(
            above(|e| e.self_penetration_relative *= 1.01),
            Some(Rejection::SelfPenetration { .. })
        ));
        assert!(matches!(
            above(|e| e.wall_penetration_relative *= 1.01),
            Some(Rejection::WallPenetration { .. })
        ));
        assert!(matches!(above(|e| e.limit_excess *= 1.01), Some(Rejection::LimitExcess { .. })));
        assert!(matches!(
            above(|e| e.limit_excess = f64::NAN),
            Some(Rejection::LimitExcess { .. })
        ));
        assert!(matches!(above(|e| e.joint_rate *= 1.01), Some(Rejection::JointRate { .. })));
        assert!(matches!(above(|e| e.joint_rate = f64::NAN), Some(Rejection::JointRate { .. })));
        assert!(matches!(above(|e| e.grip_error_cm *= 1.01), Some(Rejection::GripError { .. })));
        assert!(matches!(above(|e| e.grip_error_cm = f64::NAN), Some(Rejection::GripError { .. })));
        assert!(matches!(
            above(|e| e.inexact_residual = Some(f64::NAN)),
            Some(Rejection::InexactSolve { .. })
        ));
        assert_eq!(above(|e| e.inexact_residual = None), None);
    }

    #[test]
    fn invalid_bounds_are_refused_by_name() {
        let bad = StepAcceptance { max_limit_excess_deg: -1.0, ..StepAcceptance::default() };
        assert!(matches!(
            bad.validate(),
            Err(SimError::InvalidOption { name: "max_limit_excess_deg", .. })
        ));
        let grip = StepAcceptance { max_grip_error_cm: Some(0.0), ..StepAcceptance::default() };
        assert!(matches!(
            grip.validate(),
            Err(SimError::InvalidOption { name: "max_grip_error_cm", .. })
        ));
        let many = StepAcceptance { max_halvings: 21, ..StepAcceptance::default() };
        assert!(many.validate().is_err());
        assert!(StepAcceptance::default().validate().is_ok());
    }
}
