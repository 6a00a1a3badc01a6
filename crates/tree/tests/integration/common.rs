//! Shared test fixtures: random chains and finite-difference helpers.
use glam::{DMat3, DVec3};
use hagfish_tree::{BodySpec, Data, DofParams, JointKind, Model, ModelBuilder, Transform};
use proptest::prelude::*;

/// A random chain description: per body, (joint kind code, length, radius, mass, tilt).
#[derive(Clone, Debug)]
pub struct ChainSpec {
    pub bodies: Vec<(u8, f64, f64, f64, f64)>,
}

pub fn chain_spec(min: usize, max: usize) -> impl Strategy<Value = ChainSpec> {
    prop::collection::vec((0u8..4, 0.2f64..2.0, 0.1f64..1.0, 0.1f64..3.0, -0.5f64..0.5), min..=max)
        .prop_map(|bodies| ChainSpec { bodies })
}

/// Builds a chain: code 0 = revolute about +X, 1 = universal YZ, 2 = revolute about a tilted
/// axis, 3 = translation. Joint offsets carry a small rotation so that frames are not all aligned.
pub fn build_chain(spec: &ChainSpec, gravity: DVec3, damping: f64, stiffness: f64) -> Model {
    let parents: Vec<Option<usize>> = (0..spec.bodies.len()).map(|i| i.checked_sub(1)).collect();
    build_tree(spec, &parents, gravity, damping, stiffness)
}

/// Builds the bodies of `spec` as in [`build_chain`], but body `i` hangs from `parents[i]`
/// (`< i`, or `None` for a root), so that branches share their ancestors' DOFs.
pub fn build_tree(
    spec: &ChainSpec,
    parents: &[Option<usize>],
    gravity: DVec3,
    damping: f64,
    stiffness: f64,
) -> Model {
    let mut builder = ModelBuilder::new().gravity(gravity);
    for (i, &(code, length, radius, mass, tilt)) in spec.bodies.iter().enumerate() {
        let previous_length = parents[i].map_or(0.0, |p| spec.bodies[p].1);
        let joint = match code {
            0 => JointKind::Revolute { axis: DVec3::X },
            1 => JointKind::UniversalYz,
            2 => JointKind::Revolute { axis: DVec3::new(tilt, 1.0, 0.3).normalize() },
            _ => JointKind::Translation,
        };
        let dofs =
            vec![DofParams { stiffness, damping, ..DofParams::default() }; joint.dof_count()];
        let joint_offset = Transform {
            rotation: DMat3::from_axis_angle(DVec3::new(0.0, 1.0, 1.0).normalize(), tilt),
            translation: DVec3::new(previous_length, 0.0, 0.0),
        };
        let body = Cylinder { mass, length, radius };
        builder.add_body(body.spec(parents[i], joint, joint_offset, dofs));
    }
    builder.build().expect("valid test chain")
}

/// A solid cylinder along X: the bodies of the test chains.
#[derive(Clone, Copy, Debug)]
pub struct Cylinder {
    /// Mass (g).
    pub mass: f64,
    /// Length ℓ (cm).
    pub length: f64,
    /// Radius (cm).
    pub radius: f64,
}

impl Cylinder {
    /// The body, its centre ℓ/2 along X from its joint.
    pub fn spec(
        self,
        parent: Option<usize>,
        joint: JointKind,
        joint_offset: Transform,
        dofs: Vec<DofParams>,
    ) -> BodySpec {
        let Cylinder { mass, length, radius } = self;
        BodySpec {
            parent,
            joint,
            joint_offset,
            body_offset: Transform::from_translation(DVec3::new(length / 2.0, 0.0, 0.0)),
            mass,
            principal_inertia: cylinder_inertia(mass, radius, length),
            radius,
            length,
            skin: None,
            dofs,
        }
    }
}

/// Principal inertia of a solid cylinder along X.
pub fn cylinder_inertia(mass: f64, radius: f64, length: f64) -> DVec3 {
    let transverse = mass * (3.0 * radius * radius + length * length) / 12.0;
    DVec3::new(0.5 * mass * radius * radius, transverse, transverse)
}

pub fn vector(n: usize, scale: f64) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-scale..scale, n)
}

/// Relative error ‖a − b‖ / max(‖b‖, 1).
pub fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    let diff: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt();
    let norm: f64 = b.iter().map(|y| y * y).sum::<f64>().sqrt();
    diff / norm.max(1.0)
}

/// Kinematics at (q, q̇) into a fresh `Data`.
pub fn kinematics_at(model: &Model, q: &[f64], qdot: &[f64]) -> Data {
    let mut data = Data::new(model);
    hagfish_tree::forward_kinematics(model, q, qdot, &mut data);
    data
}

/// The vee of a skew matrix.
pub fn vee(m: DMat3) -> DVec3 {
    DVec3::new(m.y_axis.z - m.z_axis.y, m.z_axis.x - m.x_axis.z, m.x_axis.y - m.y_axis.x) * 0.5
}

/// A random tree: the bodies of a chain spec, each hanging from a random earlier body.
pub fn tree_and_position() -> impl Strategy<Value = (ChainSpec, Vec<Option<usize>>, Vec<f64>)> {
    chain_spec(2, 30).prop_flat_map(|spec| {
        let count = spec.bodies.len();
        let parents = (0..count)
            .map(|i| if i == 0 { Just(None).boxed() } else { (0..i).prop_map(Some).boxed() })
            .collect::<Vec<_>>();
        let n = build_chain(&spec, DVec3::ZERO, 0.0, 0.0).dof_count();
        (Just(spec), parents, vector(n, 1.5))
    })
}
