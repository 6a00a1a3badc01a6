//! A uniform elastic rod as a chain of the same bodies and joints as the hagfish: for checking
//! the simulator against elastic-rod theory (`docs/validation.md`). Its joint springs are
//! derived from the continuous stiffnesses (`docs/physics.md`, "Rods").

use std::f64::consts::PI;

use serde::Deserialize;

use crate::biometrics::MAX_BODY_COUNT;
use crate::error::{AnatomyError, Field, Origin};
use crate::table::{BodyRow, BodyTable, LimitDeg, joint_kind};
use crate::validate::{Bound, Checker};

/// A straight, uniform, isotropic elastic rod (a RON data file such as `data/rods/thin.ron`).
///
/// It becomes N bodies of length ℓ = L/N joined by the hagfish's alternating X-revolute
/// (twist) and YZ-universal (bend) joints, without joint limits. Bend joints sit at the odd
/// joints, 2ℓ apart, each at the midpoint of a stretch of rod 2ℓ long, so each bending DOF
/// gets the spring `k_b = B / (2ℓ)`: a moment M bends the stretch by `Mℓ·2/B`, the angle the
/// continuous rod turns through over 2ℓ. Twist joints likewise get `k_t = C / (2ℓ)` (the
/// root's twist is held by the head rows). A damping η (moment `η κ̇`) becomes `η / (2ℓ)` on
/// every DOF. The midpoint rule makes the small-deflection cantilever's tip deflection
/// `PL³/(3B) · (1 − 1/N²)`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rod {
    /// A label, e.g. "thin".
    pub name: String,
    /// Length L (cm), > 0.
    pub length_cm: f64,
    /// Radius of the circular cross-section (cm), > 0 and < 10 ℓ (a chain of bodies much
    /// shorter than they are thick is not a rod).
    pub radius_cm: f64,
    /// Number N of rigid bodies, even (pairs of twist and bend joints), in 2..=100 000.
    pub body_count: usize,
    /// Density ρ (g/cm³), > 0: the body masses are ρπr²ℓ.
    pub density_g_per_cm3: f64,
    /// Bending stiffness B = EI (dyn·cm²), > 0.
    pub bending_stiffness_dyn_cm2: f64,
    /// Twist stiffness C = GJ (dyn·cm²), ≥ 0.
    pub twist_stiffness_dyn_cm2: f64,
    /// Internal damping η (dyn·cm²·s), ≥ 0, default 0: the moment `η κ̇` on bending and twist.
    #[serde(default)]
    pub damping_dyn_cm2_s: f64,
}

impl Rod {
    /// Body length ℓ = L/N (cm).
    pub fn segment_length_cm(&self) -> f64 {
        self.length_cm / self.body_count as f64
    }

    /// Total mass ρπr²L (g).
    pub fn mass_g(&self) -> f64 {
        self.density_g_per_cm3 * PI * self.radius_cm * self.radius_cm * self.length_cm
    }

    /// The spring of each bending DOF, `B/(2ℓ)` (dyn·cm/rad).
    pub fn bend_spring_dyn_cm_per_rad(&self) -> f64 {
        self.bending_stiffness_dyn_cm2 / (2.0 * self.segment_length_cm())
    }

    /// The spring of each twist DOF, `C/(2ℓ)` (dyn·cm/rad).
    pub fn twist_spring_dyn_cm_per_rad(&self) -> f64 {
        self.twist_stiffness_dyn_cm2 / (2.0 * self.segment_length_cm())
    }

    /// The damper of every DOF, `η/(2ℓ)` (dyn·cm·s/rad).
    pub fn joint_damping_dyn_cm_s_per_rad(&self) -> f64 {
        self.damping_dyn_cm2_s / (2.0 * self.segment_length_cm())
    }

    /// Checks every value (see the field docs); errors carry [`Origin::InMemory`].
    pub fn validate(&self) -> Result<(), AnatomyError> {
        self.validate_with(&|_| Origin::InMemory)
    }

    /// [`Rod::validate`], placing each error with `locate`.
    pub(crate) fn validate_with(
        &self,
        locate: &dyn Fn(&Field) -> Origin,
    ) -> Result<(), AnatomyError> {
        let check = Checker { locate };
        check.value(Field::whole("length_cm"), self.length_cm, Bound::Positive)?;
        check.value(Field::whole("radius_cm"), self.radius_cm, Bound::Positive)?;
        let n = self.body_count;
        if !((2..=MAX_BODY_COUNT).contains(&n) && n.is_multiple_of(2)) {
            let field = Field::whole("body_count");
            return Err(AnatomyError::OutOfRange {
                at: locate(&field),
                field,
                value: n as f64,
                expected: format!(
                    "an even integer from 2 to {MAX_BODY_COUNT} (pairs of twist and bend joints)"
                ),
            });
        }
        let slender = 10.0 * self.segment_length_cm();
        if self.radius_cm >= slender {
            let field = Field::whole("radius_cm");
            return Err(AnatomyError::OutOfRange {
                at: locate(&field),
                field,
                value: self.radius_cm,
                expected: format!("below 10 body lengths, 10·L/N = {slender} cm"),
            });
        }
        check.value(Field::whole("density_g_per_cm3"), self.density_g_per_cm3, Bound::Positive)?;
        check.value(
            Field::whole("bending_stiffness_dyn_cm2"),
            self.bending_stiffness_dyn_cm2,
            Bound::Positive,
        )?;
        for (name, value) in [
            ("twist_stiffness_dyn_cm2", self.twist_stiffness_dyn_cm2),
            ("damping_dyn_cm2_s", self.damping_dyn_cm2_s),
        ] {
            check.value(Field::whole(name), value, Bound::NonNegative)?;
        }
        Ok(())
    }

    /// Validates and derives the per-body table: N equal cylinders of radius r and mass
    /// ρπr²ℓ, joints as for the hagfish ([`joint_kind`]), unlimited (±∞).
    pub fn body_table(&self) -> Result<BodyTable, AnatomyError> {
        self.validate()?;
        let n = self.body_count as f64;
        let ell = self.segment_length_cm();
        let r = self.radius_cm;
        let mass = self.density_g_per_cm3 * PI * r * r * ell;
        let unlimited = LimitDeg { lower: f64::NEG_INFINITY, upper: f64::INFINITY };
        let rows = (0..self.body_count)
            .map(|index| {
                let joint = joint_kind(index);
                BodyRow {
                    index,
                    centre_fraction: (index as f64 + 0.5) / n,
                    joint_fraction: index as f64 / n,
                    radius_cm: r,
                    mass_g: mass,
                    joint,
                    limits_deg: vec![unlimited; joint.dof_count()],
                }
            })
            .collect();
        Ok(BodyTable {
            segment_length_cm: ell,
            volume_cm3: PI * r * r * self.length_cm,
            density_g_per_cm3: self.density_g_per_cm3,
            rows,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn thin() -> Rod {
        Rod {
            name: "thin".into(),
            length_cm: 10.0,
            radius_cm: 0.05,
            body_count: 100,
            density_g_per_cm3: 1.0,
            bending_stiffness_dyn_cm2: 1000.0,
            twist_stiffness_dyn_cm2: 800.0,
            damping_dyn_cm2_s: 0.0,
        }
    }

    #[test]
    fn springs_are_the_continuous_stiffness_over_the_joint_spacing() {
        let rod = thin();
        assert!((rod.bend_spring_dyn_cm_per_rad() - 1000.0 / 0.2).abs() < 1e-9);
        assert!((rod.twist_spring_dyn_cm_per_rad() - 800.0 / 0.2).abs() < 1e-9);
        let table = rod.body_table().expect("valid");
        assert!((table.total_mass_g() - rod.mass_g()).abs() < 1e-12);
        assert!(table.rows.iter().all(|r| r.limits_deg.iter().all(|l| l.upper.is_infinite())));
    }

    #[test]
    fn odd_counts_thick_bodies_and_soft_rods_are_refused() {
        let odd = Rod { body_count: 101, ..thin() };
        assert!(odd.validate().is_err());
        let thick = Rod { radius_cm: 1.0, ..thin() };
        assert!(thick.validate().is_err(), "r = 1 cm ≥ 10 ℓ = 1 cm");
        let soft = Rod { bending_stiffness_dyn_cm2: 0.0, ..thin() };
        assert!(soft.validate().is_err());
        let nan = Rod { density_g_per_cm3: f64::NAN, ..thin() };
        assert!(nan.validate().is_err());
    }
}
