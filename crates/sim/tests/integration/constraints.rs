//! The constraint rows in the whole pipeline: on the 100-body ES103 hagfish the head stays
//! fixed, and joint limits and the wall hold while a force drives the tail around for 10 s at
//! h = 0.01 s; and one test per row type with hand-checked signs on small chains.

use crate::common::SweepingTailForce;
use glam::DVec3;
use hagfish_control::{Actuation, ControlContext, Controller, Passive, PointForce};
use hagfish_sim::rows::{Friction, MAX_FRICTION_EDGES, RowGroup, contact_directions};
use hagfish_sim::{StepOptions, World};
use hagfish_solver::SolvePath;
use hagfish_tree::{BodySpec, Data, DofParams, JointKind, Model, ModelBuilder, State, Transform};

fn hagfish() -> Model {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/hagfish/es103.ron");
    hagfish_anatomy::Biometrics::load(path).and_then(|b| b.to_model()).expect("ES103 builds")
}

/// A constant force at the centre of one body.
struct ConstantForce(usize, DVec3);

impl Controller for ConstantForce {
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        out.forces.push(PointForce { body: self.0, point: context.centre(self.0), force: self.1 });
    }
}

/// 20 dyn: in vacuum (no water drag) stronger forces whip the 0.54 g tail past 50 rad/s;
/// `docs/physics.md` records what happens then.
#[test]
fn head_limits_and_wall_hold_under_a_sweeping_tail_force() {
    let model = hagfish();
    let state = State::rest(&model);
    let mut world = World::new(model, StepOptions::default(), state).expect("world");
    let mut force = SweepingTailForce(20.0);
    let (mut head_error, mut limit_excess, mut wall_depth) = (0.0f64, 0.0f64, 0.0f64);
    let (mut limit_rows, mut wall_rows, mut qp_steps) = (0, 0, 0);
    // A point on the head body's surface, off the twist axis, at rest.
    let head_point = DVec3::new(0.212, 0.89, 0.0);
    let head_rest = world.data().tree.body_frames[0].transform_point(head_point);
    for _ in 0..1000 {
        let report = *world.step(&mut force).expect("step succeeds");
        limit_rows = limit_rows.max(report.solve.rows_per_tag[RowGroup::Limit.tag()]);
        wall_rows = wall_rows.max(report.solve.rows_per_tag[RowGroup::Wall.tag()]);
        qp_steps += usize::from(report.solve.path == SolvePath::Qp);
        let frames = &world.data().tree.body_frames;
        head_error = head_error.max((frames[0].transform_point(head_point) - head_rest).length());
        let model = world.model();
        for (k, dof) in model.dofs().iter().enumerate() {
            let q = world.state().q[k];
            limit_excess = limit_excess.max(dof.lower - q).max(q - dof.upper);
        }
        for (i, body) in model.bodies().iter().enumerate().skip(3) {
            wall_depth = wall_depth.max((body.radius - frames[i].translation.x) / body.radius);
        }
    }
    println!(
        "head error {head_error:.3e} cm; max limit excess {:.4}°; max wall depth {:.3} % of r; \
         max rows: limit {limit_rows}, wall {wall_rows}; QP steps {qp_steps}",
        limit_excess.to_degrees(),
        100.0 * wall_depth
    );
    assert!(limit_rows > 0 && wall_rows > 0, "the scenario must exercise limits and the wall");
    assert!(head_error < 1e-6, "head moved by {head_error} cm");
    assert!(limit_excess.to_degrees() < 0.5, "limit exceeded by {}°", limit_excess.to_degrees());
    assert!(wall_depth < 0.02, "wall penetration {wall_depth} of a radius");
}

/// A planar chain of `bodies` 1 cm, 1 g rods of radius 0.2 cm hinged about +Z at their ends,
/// lying along +X from the origin, each joint limited to ±`limit` rad.
pub(crate) fn planar_chain(bodies: usize, limit: f64) -> Model {
    let mut builder = ModelBuilder::new();
    for i in 0..bodies {
        let dof = DofParams { lower: -limit, upper: limit, ..DofParams::default() };
        builder.add_body(BodySpec {
            parent: i.checked_sub(1),
            joint: JointKind::Revolute { axis: DVec3::Z },
            joint_offset: Transform::from_translation(DVec3::new(
                if i == 0 { 0.0 } else { 1.0 },
                0.0,
                0.0,
            )),
            body_offset: Transform::from_translation(DVec3::new(0.5, 0.0, 0.0)),
            mass: 1.0,
            principal_inertia: DVec3::new(0.02, 0.1, 0.1),
            radius: 0.2,
            length: 1.0,
            skin: None,
            dofs: vec![dof],
        });
    }
    builder.build().expect("valid chain")
}

fn options_without_contacts() -> StepOptions {
    StepOptions { self_contact: false, wall: None, ..StepOptions::default() }
}

#[test]
fn upper_limit_row_stops_the_joint_and_pushes_back() {
    // Joint 1 at its upper limit, driven further by a force at the tip: the limit row must
    // hold q₁ ≤ hi with λ > 0, and its generalized force must oppose the drive. (Joint 0 is a
    // root, held by the head row.)
    let model = planar_chain(2, 0.3);
    let mut state = State::rest(&model);
    state.q[1] = 0.3;
    let mut world = World::new(model, options_without_contacts(), state).expect("world");
    let mut push = ConstantForce(1, DVec3::new(0.0, 5.0, 0.0)); // +y on rod 1: drives +q₁
    for _ in 0..20 {
        world.step(&mut push).expect("step");
        let data = world.data();
        let limit_rows: Vec<usize> = (0..data.rows.len())
            .filter(|&i| data.rows.sources()[i].tag == RowGroup::Limit.tag())
            .collect();
        assert_eq!(limit_rows.len(), 1, "exactly the upper row of joint 1");
        let lambda = data.solver.multipliers()[limit_rows[0]];
        assert!(lambda > 0.0, "λ = {lambda}");
        let mut force = vec![0.0; 2];
        data.group_force(RowGroup::Limit, world.options().time_step, &mut force);
        assert!(force[1] < 0.0, "the limit pushes q₁ down: {force:?}");
        assert!(world.state().q[1] <= 0.3 + 1e-12, "q₁ = {}", world.state().q[1]);
    }
}

#[test]
fn lower_limit_row_stops_the_joint() {
    let model = planar_chain(2, 0.3);
    let mut state = State::rest(&model);
    state.q[1] = -0.29;
    state.qdot[1] = -5.0; // would reach −0.34 in one step
    let mut world = World::new(model, options_without_contacts(), state).expect("world");
    world.step(&mut Passive).expect("step");
    let data = world.data();
    let row = (0..data.rows.len())
        .find(|&i| data.rows.sources()[i].tag == RowGroup::Limit.tag())
        .expect("row");
    assert_eq!(data.rows.row(row).expect("row").to_vec()[1], 1.0);
    assert!(data.solver.multipliers()[row] > 0.0);
    assert!(
        (world.state().q[1] + 0.3).abs() < 1e-12,
        "q₁ lands on the limit: {}",
        world.state().q[1]
    );
}

#[test]
fn wall_row_stops_a_body_pushed_into_the_wall() {
    // Rod 0 hinged at the origin about +Z; body 1's centre is pushed toward −X into the wall
    // x = 0 (normal +X). The wall row must get λ > 0 and keep the sphere out.
    let model = planar_chain(3, 3.0);
    let mut state = State::rest(&model);
    state.q[1] = 2.0; // fold bodies 1 and 2 back toward the wall
    let options = StepOptions {
        self_contact: false,
        wall_options: hagfish_geometry::WallOptions { margin: 0.2, first_body: 2 },
        ..StepOptions::default()
    };
    let mut world = World::new(model, options, state).expect("world");
    let mut push = ConstantForce(2, DVec3::new(-50.0, 30.0, 0.0));
    let mut saw_wall = false;
    for _ in 0..100 {
        world.step(&mut push).expect("step");
        let data = world.data();
        for i in
            (0..data.rows.len()).filter(|&i| data.rows.sources()[i].tag == RowGroup::Wall.tag())
        {
            let lambda = data.solver.multipliers()[i];
            assert!(lambda >= 0.0);
            saw_wall |= lambda > 0.0;
        }
        let x = centre(&world, 2).x;
        assert!(x > 0.2 * (1.0 - 0.02), "body 2 entered the wall: centre x = {x}");
    }
    assert!(saw_wall, "the wall never pushed");
}

/// A three-rod chain (rod 0 held, hinges at x = 1 and 2), bent (q₁ = −0.3, q₂ = 0.6) so that
/// rod 2's sphere rests on a wall y = const below it (normal +y), pressed by 50 dyn and pushed
/// along the wall (−x) by 10: frictionless the chain folds and rod 2 slides along the wall;
/// with μ = 0.5 (limit 25 dyn) friction holds it, and each wall contact's impulse lies in the
/// cone ‖λ_t‖ ≤ μλ_n (summed over its pyramid's edges). With μ = 0 the run is the frictionless
/// one, bit for bit.
#[test]
fn wall_friction_holds_a_body_that_the_frictionless_wall_lets_slide() {
    let (q1, q2) = (-0.3_f64, 0.6_f64);
    let rest_y = q1.sin() + 0.5 * (q1 + q2).sin();
    let run = |friction: Option<Friction>| {
        let model = planar_chain(3, 3.0);
        let mut state = State::rest(&model);
        (state.q[1], state.q[2]) = (q1, q2);
        let options = StepOptions {
            self_contact: false,
            wall: Some((DVec3::new(0.0, rest_y - 0.2, 0.0), DVec3::Y)),
            wall_options: hagfish_geometry::WallOptions { margin: 0.1, first_body: 2 },
            friction,
            ..StepOptions::default()
        };
        let mut world = World::new(model, options, state).expect("world");
        let mut push = ConstantForce(2, DVec3::new(-10.0, -50.0, 0.0));
        let start = centre(&world, 2);
        let mut worst_cone = 0.0_f64;
        let mu = friction.map_or(0.0, |f| f.coefficient);
        for _ in 0..100 {
            world.step(&mut push).expect("step");
            let data = world.data();
            let mut directions = [DVec3::ZERO; MAX_FRICTION_EDGES];
            let (mut normal, mut tangent, mut edge) = (0.0, DVec3::ZERO, 0);
            for i in 0..data.rows.len() {
                if data.rows.sources()[i].tag != RowGroup::Wall.tag() {
                    continue;
                }
                let contact = &data.wall_contacts[data.rows.sources()[i].id];
                let edges = contact_directions(contact.normal, DVec3::X, friction, &mut directions);
                let impulse = data.solver.multipliers()[i] * directions[edge % edges];
                edge += 1;
                normal += impulse.dot(contact.normal);
                tangent += impulse - impulse.dot(contact.normal) * contact.normal;
            }
            worst_cone = worst_cone.max(tangent.length() - mu * normal);
        }
        (centre(&world, 2) - start, world.state().clone(), worst_cone)
    };
    let (frictionless, plain, _) = run(None);
    let (held, _, cone) = run(Some(Friction::pyramid(0.5, 8)));
    let (zero, zero_state, _) = run(Some(Friction::pyramid(0.0, 8)));
    println!("displacement of rod 2: frictionless {frictionless}, μ = 0.5 {held}");
    assert!(frictionless.x < -0.2, "frictionless, rod 2 slides along the wall: {frictionless}");
    assert!(held.x.abs() < 0.1 * frictionless.x.abs(), "friction holds it: {held}");
    assert!(cone <= 1e-9, "a wall impulse outside the cone by {cone}");
    assert_eq!(zero, frictionless);
    assert_eq!(zero_state.q, plain.q, "μ = 0 is the frictionless run, bit for bit");
}

fn centre(world: &World, body: usize) -> DVec3 {
    let mut data = Data::new(world.model());
    hagfish_tree::forward_kinematics(
        world.model(),
        &world.state().q,
        &world.state().qdot,
        &mut data,
    );
    data.body_centre(body)
}

/// Rod 2 of a straight chain pushed down (−y, 50 dyn) onto an obstacle just below it — a
/// plane, a sphere, an infinite and a finite cylinder across the chain — is stopped by it: its
/// sphere never sinks more than 2 % of its radius into the obstacle, and the obstacle pushes.
#[test]
fn obstacles_stop_a_body_pushed_into_them() {
    use hagfish_geometry::Obstacle;
    let below = DVec3::new(2.5, -0.25, 0.0); // rod 2's centre is (2.5, 0, 0), radius 0.2
    let obstacles = [
        Obstacle::plane(below, DVec3::Y),
        Obstacle::sphere(below - DVec3::new(0.0, 1.0, 0.0), 1.0),
        Obstacle::cylinder(below - DVec3::new(0.0, 0.5, 0.0), DVec3::Z, 0.5, None),
        Obstacle::cylinder(below - DVec3::new(0.0, 0.5, 0.0), DVec3::Z, 0.5, Some(0.3)),
    ];
    for obstacle in obstacles {
        let obstacle = obstacle.expect("a valid obstacle");
        let model = planar_chain(3, 3.0);
        let state = State::rest(&model);
        let options = StepOptions {
            self_contact: false,
            wall: None,
            obstacles: vec![obstacle.into()],
            ..StepOptions::default()
        };
        let mut world = World::new(model, options, state).expect("world");
        let mut push = ConstantForce(2, DVec3::new(0.0, -50.0, 0.0));
        let mut pushed = false;
        for _ in 0..100 {
            world.step(&mut push).expect("step");
            let data = world.data();
            for (i, source) in data.rows.sources().iter().enumerate() {
                pushed |= source.tag == RowGroup::Wall.tag() && data.solver.multipliers()[i] > 0.0;
            }
            let (distance, _) = obstacle.distance(centre(&world, 2));
            assert!(distance - 0.2 > -0.02 * 0.2, "{obstacle:?}: rod 2 sank {}", 0.2 - distance);
        }
        assert!(pushed, "{obstacle:?} never pushed");
    }
}
