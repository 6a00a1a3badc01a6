//! An obstacle moving on a path pushes what it meets, and one turning in place drags it by
//! friction: its contacts bound the body's velocity relative to its surface.

use glam::DVec3;
use hagfish_control::Passive;
use hagfish_geometry::{MovingObstacle, Obstacle, ObstaclePath, Spin};
use hagfish_sim::rows::Friction;
use hagfish_sim::{RootHold, StepOptions, World};
use hagfish_tree::{BodySpec, DofParams, JointKind, Model, ModelBuilder, State, Transform};

/// A free block: two welded 1 cm, 1 g bodies (radius 0.2 cm) along +x from the origin on a
/// translation root, no gravity.
fn block() -> Model {
    let mut builder = ModelBuilder::new();
    for spec in block_bodies() {
        builder.add_body(spec);
    }
    builder.build().expect("a valid block")
}

/// The bodies of [`block`].
fn block_bodies() -> [BodySpec; 2] {
    [0_usize, 1].map(|i| {
        let (joint, offset, dofs) = match i {
            0 => (JointKind::Translation, Transform::IDENTITY, vec![DofParams::default(); 3]),
            _ => (JointKind::Fixed, Transform::from_translation(DVec3::X), Vec::new()),
        };
        BodySpec {
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
        }
    })
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
    let moving = MovingObstacle { shape: sphere, path, spin: None };
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

/// The block of [`block`] (2 g) lying on top of a roller: a cylinder of radius R = 10⁴ cm
/// about an axis along z below the block's middle, where its tube touches it (at the two
/// centres and the eight samples between them),
/// turning at ω = −5·10⁻⁴ rad/s, so that its top moves along +x at ωR = 5 cm/s; gravity −g ŷ,
/// μ = 0.05 (8-edge pyramid, an edge along x). The block slips and is dragged along at a = μg
/// until it moves with the surface (5 cm/s after 0.1 s, 0.26 cm along), then rides on it:
/// Coulomb's kinetic friction, then sticking, on a surface that turns in place. The surface
/// under the block tilts by ±5·10⁻⁵ rad, and by 2.6·10⁻⁵ rad more along the slip: each
/// 0.1 % of μ at most, however the contacts share the load.
#[test]
fn a_turning_roller_drags_a_block_at_mu_g_until_it_moves_with_its_surface() {
    const G: f64 = 980.0;
    let (radius, rate, mu, h) = (1e4, -5e-4, 0.05, 0.005);
    let depth = ((radius + 0.2_f64).powi(2) - 0.25).sqrt();
    let roller =
        Obstacle::cylinder(DVec3::new(1.0, -depth, 0.0), DVec3::Z, radius, None).expect("a roller");
    let spin = Spin::new(&roller, DVec3::Z, rate).expect("about its own axis");
    let turning = MovingObstacle { shape: roller, path: ObstaclePath::default(), spin: Some(spin) };
    let options = StepOptions {
        time_step: h,
        self_contact: false,
        wall: None,
        root: RootHold::Free,
        friction: Some(Friction::pyramid(mu, 8)),
        obstacles: vec![turning],
        ..StepOptions::default()
    };
    let mut builder = ModelBuilder::new().gravity(DVec3::new(0.0, -G, 0.0));
    for spec in block_bodies() {
        builder.add_body(spec);
    }
    let model = builder.build().expect("a valid block");
    let state = State::rest(&model);
    let mut world = World::new(model, options, state).expect("world");
    let surface_speed = -rate * radius;
    let mut velocities = vec![0.0];
    for _ in 0..60 {
        world.step(&mut Passive).expect("step");
        velocities.push(world.state().qdot[0]);
    }
    // Slipping (up to 0.1 s): the velocity along x grows by μgh a step. The first step lifts
    // the block off the surface at μ|v_rel| = 0.25 cm/s (Anitescu's relaxation, as on the
    // incline: its normal impulse carries that lift, and friction with it) and the second
    // lands it: over the two the velocity grows by 2μgh.
    let start = velocities[2] / (2.0 * h);
    assert!((start - mu * G).abs() < 0.01 * mu * G, "steps 1–2: a = {start} cm/s²");
    for (step, pair) in velocities[2..=20].windows(2).enumerate() {
        let acceleration = (pair[1] - pair[0]) / h;
        let relative = (acceleration - mu * G).abs() / (mu * G);
        assert!(relative < 0.01, "step {}: a = {acceleration} cm/s², μg = {}", step + 3, mu * G);
    }
    // Caught up (from 0.11 s): it moves with the surface.
    for (step, &v) in velocities.iter().enumerate().skip(22) {
        assert!((v - surface_speed).abs() < 1e-3 * surface_speed, "step {step}: {v} cm/s");
    }
}
