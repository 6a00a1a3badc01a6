//! Uniform long chains, the bodies of the scaling benchmark (`benches/scaling.rs`) and of
//! the step's memory and sparse-backend tests: `bodies` ES103-like segments of the same
//! length, so 200, 400 or 1000 bodies make a longer animal, not a finer one.
//!
//! ```
//! let chain = hagfish_anatomy::segment_chain(20)?;
//! assert_eq!((chain.body_count(), chain.dof_count()), (20, 30));
//! # Ok::<(), hagfish_tree::TreeError>(())
//! ```

use glam::DVec3;
use hagfish_tree::{BodySpec, DofParams, JointKind, Model, ModelBuilder, Transform, TreeError};

/// A chain of `bodies` segments along +X, each ℓ = 0.424 cm long, of mass 0.8 g and radius
/// 0.85 cm (solid cylinder: `I = (m r²/2, m(3r² + ℓ²)/12, m(3r² + ℓ²)/12)`), joints
/// alternating X-revolute (twist, ±48°) and YZ-universal (bend, ±45°), stiffness
/// 1 dyn·cm/rad, damping 0.1 dyn·cm·s/rad, root joint at the origin: 1.5 DOFs per body.
pub fn segment_chain(bodies: usize) -> Result<Model, TreeError> {
    let mut builder = ModelBuilder::new();
    let (length, mass, radius) = (0.424, 0.8, 0.85);
    let transverse = mass * (3.0 * radius * radius + length * length) / 12.0;
    for i in 0..bodies {
        let (joint, limit) = if i % 2 == 0 {
            (JointKind::Revolute { axis: DVec3::X }, 48f64.to_radians())
        } else {
            (JointKind::UniversalYz, 45f64.to_radians())
        };
        let dof = DofParams {
            stiffness: 1.0,
            damping: 0.1,
            lower: -limit,
            upper: limit,
            ..DofParams::default()
        };
        let offset = if i == 0 { 0.0 } else { length };
        builder.add_body(BodySpec {
            parent: i.checked_sub(1),
            joint,
            joint_offset: Transform::from_translation(DVec3::new(offset, 0.0, 0.0)),
            body_offset: Transform::from_translation(DVec3::new(length / 2.0, 0.0, 0.0)),
            mass,
            principal_inertia: DVec3::new(0.5 * mass * radius * radius, transverse, transverse),
            radius,
            length,
            skin: None,
            dofs: vec![dof; joint.dof_count()],
        });
    }
    builder.build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chain_has_one_and_a_half_dofs_per_body_and_limits() -> Result<(), TreeError> {
        let model = segment_chain(10)?;
        assert_eq!(model.body_count(), 10);
        assert_eq!(model.dof_count(), 15);
        assert!((model.dofs()[0].upper - 48f64.to_radians()).abs() < 1e-15);
        assert!((model.dofs()[1].lower + 45f64.to_radians()).abs() < 1e-15);
        Ok(())
    }
}
