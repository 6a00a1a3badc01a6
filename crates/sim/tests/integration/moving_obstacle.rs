//! An obstacle moving on a path pushes what it meets: its contacts bound the body's velocity
//! relative to its surface.

use glam::DVec3;
use hagfish_control::Passive;
use hagfish_geometry::{MovingObstacle, Obstacle, ObstaclePath};
use hagfish_sim::{RootHold, StepOptions, World};
use hagfish_tree::{BodySpec, DofParams, JointKind, Model, ModelBuilder, State, Transform};

/// A free block: two welded 1 cm, 1 g bodies (radius 0.2 cm) along +x from the origin on a
/// translation root, no gravity.
fn block() -> Model {
    let mut builder = ModelBuilder::new();
    for i in 0..2_usize {
        let (joint, offset, dofs) = match i {
            0 => (JointKind::Translation, Transform::IDENTITY, vec![DofParams::default(); 3]),
            _ => (JointKind::Fixed, Transform::from_translation(DVec3::X), Vec::new()),
        };
        builder.add_body(BodySpec {
            parent: i.checked_sub(1),
            joint,
            joint_offset: offset,
            body_offset: Transform::from_translation(DVec3::X * 0.5),
            mass: 1.0,
            principal_inertia: DVec3::new(0.02, 0.1, 0.1),
            radius: 0.2,
            length: 1.0,
            skin: None,
            dofs,
        });
    }
    builder.build().expect("a valid block")
}

/// A sphere of radius 1 cm starting 3 cm above the block's middle (gap 1.8 cm) and moving down
/// (−y) at 5 cm/s for 10 s reaches the block after 0.36 s and carries it along: from 0.42 s
/// on the block moves at the sphere's −5 cm/s (within 10⁻⁹; checked from 0.45 s), never more
/// than 2 % of its radius into the sphere; before contact it does not move.
#[test]
fn a_sphere_moving_on_its_path_pushes_a_free_block_at_its_own_speed() {
    let sphere = Obstacle::sphere(DVec3::new(1.0, 3.0, 0.0), 1.0).expect("a sphere");
    let path = ObstaclePath::new(vec![(0.0, DVec3::ZERO), (10.0, DVec3::new(0.0, -50.0, 0.0))])
        .expect("a path");
    let moving = MovingObstacle { shape: sphere, path };
    let options = StepOptions {
        self_contact: false,
        wall: None,
        root: RootHold::Free,
        obstacles: vec![moving.clone()],
        ..StepOptions::default()
    };
    let model = block();
    let state = State::rest(&model);
    let mut world = World::new(model, options, state).expect("world");
    for step in 1..=100 {
        world.step(&mut Passive).expect("step");
        let (t, velocity) = (world.state().t, world.state().qdot[1]);
        if t < 0.35 {
            assert_eq!(velocity, 0.0, "step {step}: the block moved before contact");
        } else if t > 0.45 {
            assert!((velocity + 5.0).abs() < 1e-9, "step {step}: block at {velocity} cm/s");
        }
        let bodies = [0.5, 1.5].map(|x| DVec3::new(x, world.state().q[1], 0.0));
        for body in bodies {
            let (d, _) = moving.at(t).distance(body);
            assert!(d - 0.2 > -0.02 * 0.2, "step {step}: a body {} cm deep", 0.2 - d);
        }
    }
}
