//! Obstacles touch the tube, not only the bodies' spheres: a thin bar under a rod of bodies
//! long against their radius holds it where a chain of beads falls through.

use crate::constraints::planar_chain;
use glam::DVec3;
use hagfish_control::Passive;
use hagfish_geometry::{Centreline, DEFAULT_GROOVE_FRACTION, Obstacle, TubeSamples};
use hagfish_sim::rows::RowGroup;
use hagfish_sim::{RootHold, StepData, StepOptions, World, pipeline};
use hagfish_tree::{BodySpec, DofParams, JointKind, ModelBuilder, State, Transform};

const RADIUS: f64 = 0.3;
const BAR: f64 = 0.05;
const BAR_X: f64 = 2.0 + 1.0 / 12.0;

/// A straight rod of four welded 1 cm, 1 g bodies of radius 0.3 cm along +x on a translation
/// root (centres at x = 0.5 … 3.5), under gravity −g ŷ, above a bar of radius 0.05 cm along z
/// at x = 2 + 1/12 (between two centres, and midway between two of the default samples, 1/6 cm
/// apart) whose top is 0.01 cm below the tube: the bodies' spheres leave 0.4 cm between them,
/// so the bar fits through. Run
/// for 0.3 s at h = 0.005 s with the obstacles seeing the tube as `groove` says; returns the
/// rod's drop (cm) and the tube's deepest overlap with the bar at the end (cm, by the axis
/// sampled every 0.001 cm).
fn drop_onto_a_bar(groove: Option<f64>) -> (f64, f64) {
    let mut builder = ModelBuilder::new().gravity(DVec3::new(0.0, -980.0, 0.0));
    for i in 0..4_usize {
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
            principal_inertia: DVec3::new(0.05, 0.1, 0.1),
            radius: RADIUS,
            length: 1.0,
            skin: None,
            dofs,
        });
    }
    let model = builder.build().expect("a valid rod");
    let bar =
        Obstacle::cylinder(DVec3::new(BAR_X, -(RADIUS + BAR + 0.01), 0.0), DVec3::Z, BAR, None)
            .expect("a bar");
    let options = StepOptions {
        time_step: 0.005,
        self_contact: false,
        wall: None,
        root: RootHold::Free,
        obstacles: vec![bar.into()],
        obstacle_groove: groove,
        ..StepOptions::default()
    };
    let state = State::rest(&model);
    let mut world = World::new(model, options, state).expect("world");
    for _ in 0..60 {
        world.step(&mut Passive).expect("step");
    }
    let mut centres = vec![DVec3::ZERO; 4];
    world.body_centres(&mut centres);
    let line = Centreline::new(&centres, &[RADIUS; 4]).expect("a centreline");
    let overlap = (0..=3000)
        .map(|i| RADIUS - bar.distance(line.point(f64::from(i) / 1000.0)).0)
        .fold(f64::NEG_INFINITY, f64::max);
    (-world.state().q[1], overlap)
}

/// With the default samples (f = 0.05: six a segment here) the bar holds the rod: after 0.3 s
/// the tube overlaps it by no more than the groove between two samples at the bar,
/// (r + R) − √((r + R)² − δ²/4) = 0.0101 cm for δ = 1/6 cm (5 % of the radius at most), and the
/// rod has dropped by the 0.01 cm gap and that overlap. As a chain of beads
/// (`obstacle_groove: None`) it falls through, 44 cm in 0.3 s.
#[test]
fn a_thin_bar_holds_the_tube_where_the_bodies_spheres_fall_through() {
    let (drop, overlap) = drop_onto_a_bar(Some(DEFAULT_GROOVE_FRACTION));
    let groove = TubeSamples::groove_depth(1.0 / 6.0, RADIUS + BAR);
    println!(
        "tube: dropped {drop:.5} cm, overlaps the bar by {overlap:.5} cm (groove {groove:.5})"
    );
    assert!(overlap > 0.0 && overlap <= groove + 1e-4, "overlap {overlap} cm, groove {groove} cm");
    assert!(groove <= DEFAULT_GROOVE_FRACTION * RADIUS);
    assert!((drop - (0.01 + overlap)).abs() < 1e-4, "dropped {drop} cm");
    let (fallen, _) = drop_onto_a_bar(None);
    println!("beads: dropped {fallen:.2} cm");
    assert!(fallen > 40.0, "the beads fell {fallen} cm");
}

/// [`planar_chain`] of five bodies bent at `q`: nine samples a segment at the default groove
/// (δ_max = 0.1249 cm).
fn bent_chain(q: &[f64]) -> (hagfish_tree::Model, State) {
    let model = planar_chain(5, 3.0);
    let mut state = State::rest(&model);
    state.q.copy_from_slice(q);
    (model, state)
}

/// The row of a sample between two centres is nᵀ ẋ(u) with ẋ(u) = Σ w_m ċ_m, the blend of its
/// bodies' centre velocities: on the bent chain moving at q̇, every obstacle row times q̇ equals
/// n·ẋ(u) from a central difference of the centres (step 10⁻⁶ along q̇), within 10⁻⁸ cm/s.
#[test]
fn a_sample_between_centres_bounds_the_velocity_of_its_spline_point() {
    let q = [0.3, -0.5, 0.7, 0.4, -0.6];
    let qdot = [0.8, -1.3, 0.6, 2.1, -0.9];
    let (model, state) = bent_chain(&q);
    let sphere = Obstacle::sphere(DVec3::new(2.2, 1.2, 0.0), 0.6).expect("a sphere");
    let options = StepOptions {
        self_contact: false,
        wall: None,
        obstacles: vec![sphere.into()],
        ..StepOptions::default()
    };
    let mut data = StepData::new(&model, &options).expect("step data");
    pipeline::kinematics(&model, &state, &mut data);
    pipeline::detect_contacts(&model, &options, 0.0, &mut data).expect("contacts");
    pipeline::build_rows(&model, &options, &state, &mut data);
    let centres_at = |sign: f64| {
        let q: Vec<f64> = q.iter().zip(qdot).map(|(q, v)| q + sign * 1e-6 * v).collect();
        let (model, state) = bent_chain(&q);
        let mut world = World::new(model, StepOptions::default(), state).expect("world");
        let mut centres = Vec::new();
        world.body_centres(&mut centres);
        centres
    };
    let (ahead, behind) = (centres_at(1.0), centres_at(-1.0));
    let mut between = 0;
    for (i, source) in data.rows.sources().iter().enumerate() {
        if source.tag != RowGroup::Wall.tag() {
            continue;
        }
        let contact = &data.wall_contacts[source.id];
        between += usize::from(contact.body().is_none());
        let row = data.rows.row(i).expect("a row of its own").to_vec();
        let rate: f64 = row.iter().zip(qdot).map(|(a, v)| a * v).sum();
        let velocity: DVec3 =
            contact.weights.iter().map(|(m, w)| w * (ahead[m] - behind[m]) / 2e-6).sum();
        let expected = contact.normal.dot(velocity);
        assert!((rate - expected).abs() < 1e-8, "u = {}: {rate} vs {expected}", contact.u);
    }
    assert!(between >= 3, "{between} samples between centres touch the sphere");
}
