//! Building the kinematic tree from the body table : a chain along +X,
//! the root joint anchored at the wall point (the world origin), gravity off (D4).

use glam::DVec3;
use hagfish_tree::{BodySpec, DofParams, JointKind, Model, ModelBuilder, Skin, Transform};

use crate::biometrics::{Biometrics, BodySkin};
use crate::error::AnatomyError;
use crate::rod::Rod;
use crate::table::{BodyRow, BodyTable};

/// Principal inertia (g·cm²) of a solid cylinder of mass `m`, radius `r` and length `ℓ`
/// along X about its centre: `I₁ = ½ m r²`, `I₂ = I₃ = m (3r² + ℓ²) / 12` (docs/physics.md, "Body").
pub fn cylinder_inertia(mass: f64, radius: f64, length: f64) -> DVec3 {
    let transverse = mass * (3.0 * radius * radius + length * length) / 12.0;
    DVec3::new(0.5 * mass * radius * radius, transverse, transverse)
}

impl Biometrics {
    /// Builds the model (the chain of `build_chain`): each DOF gets the stiffness of its joint
    /// type and the common damping, both scaled to this body count
    /// ([`Biometrics::joint_bending_stiffness`] and its siblings, D16), rest 0 and the table's
    /// limits in radians, and the skin if the body has one. Gravity is zero (neutral buoyancy,
    /// D4).
    pub fn to_model(&self) -> Result<Model, AnatomyError> {
        build_chain(&self.body_table()?, self.skin, |row| {
            let stiffness = match row.joint {
                JointKind::Revolute { .. } => self.joint_twist_stiffness(),
                _ => self.joint_bending_stiffness(),
            };
            (stiffness, self.joint_damping())
        })
    }
}

impl Rod {
    /// Builds the model (the chain of `build_chain`) with the springs and dampers derived from the
    /// continuous stiffnesses ([`Rod::bend_spring_dyn_cm_per_rad`] and its siblings), no
    /// limits, gravity zero.
    pub fn to_model(&self) -> Result<Model, AnatomyError> {
        let damping = self.joint_damping_dyn_cm_s_per_rad();
        build_chain(&self.body_table()?, None, |row| match row.joint {
            JointKind::Revolute { .. } => (self.twist_spring_dyn_cm_per_rad(), damping),
            _ => (self.bend_spring_dyn_cm_per_rad(), damping),
        })
    }
}

/// Builds the chain of `table` along +X: body `i` hangs from joint `i` at its proximal end,
/// with its frame at its centre (`body_offset = (ℓ/2, 0, 0)`); joint 0 is the root at the
/// world origin, joint `i ≥ 1` sits at `(ℓ, 0, 0)` in joint `i − 1`'s frame; solid-cylinder
/// inertias. `spring_and_damper(row)` gives the stiffness (dyn·cm/rad) and damping
/// (dyn·cm·s/rad) of every DOF of the row's joint; rest 0, limits from the table in radians.
/// With a `skin`, every body gets it at its own radius (thickness `fraction·r`).
fn build_chain(
    table: &BodyTable,
    skin: Option<BodySkin>,
    spring_and_damper: impl Fn(&BodyRow) -> (f64, f64),
) -> Result<Model, AnatomyError> {
    let ell = table.segment_length_cm;
    let mut builder = ModelBuilder::new().gravity(DVec3::ZERO);
    for row in &table.rows {
        let (parent, joint_offset) = match row.index {
            0 => (None, Transform::IDENTITY),
            i => (Some(i - 1), Transform::from_translation(DVec3::new(ell, 0.0, 0.0))),
        };
        let (stiffness, damping) = spring_and_damper(row);
        let dofs = row
            .limits_deg
            .iter()
            .map(|limit| DofParams {
                stiffness,
                damping,
                rest: 0.0,
                lower: limit.lower.to_radians(),
                upper: limit.upper.to_radians(),
            })
            .collect();
        builder.add_body(BodySpec {
            parent,
            joint: row.joint,
            joint_offset,
            body_offset: Transform::from_translation(DVec3::new(0.5 * ell, 0.0, 0.0)),
            mass: row.mass_g,
            principal_inertia: cylinder_inertia(row.mass_g, row.radius_cm, ell),
            radius: row.radius_cm,
            length: ell,
            skin: skin.map(|s| Skin {
                thickness: s.thickness_fraction * row.radius_cm,
                pressure: s.pressure_dyn_per_cm2,
            }),
            dofs,
        });
    }
    Ok(builder.build()?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylinder_inertia_matches_formula() {
        let i = cylinder_inertia(2.0, 0.5, 1.0);
        assert!((i.x - 0.25).abs() < 1e-15);
        assert!((i.y - 2.0 * (0.75 + 1.0) / 12.0).abs() < 1e-15);
        assert_eq!(i.y, i.z);
    }
}
