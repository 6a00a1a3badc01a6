//! An initial shape read from a vertex file: Choi et al.'s overhand knots with n = 1…4 turns
//! (`data/knots/imc-der/`), laid onto the 600-body rod of `data/rods/choi2021.ron`, are the
//! (2, 2n + 1) torus knots 3₁, 5₁, 7₁ and 9₁ (Alexander polynomial t^2n − t^(2n−1) + … + 1,
//! by closure over many directions), their bending joints lie on the curve, and a vertex file
//! that is not a curve is refused at the scenario's `file`.

use glam::DVec3;
use hagfish_knots::{KnotOptions, analyse_knot};
use hagfish_scenario::{InitialShape, LoadedScenario, Override};
use hagfish_tree::{Data, position_kinematics};

const SCENARIO: &str =
    concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/imc_overhand.ron");

/// The tree kinematics of the scenario's world at t = 0.
fn posed(loaded: &LoadedScenario) -> (Data, usize) {
    let (world, _) = loaded.build().expect("a world");
    let model = world.model();
    let mut data = Data::new(model);
    position_kinematics(model, &world.state().q, &mut data);
    (data, model.body_count())
}

/// The scenario with the knot of `turns` turns.
fn overhand(turns: usize) -> LoadedScenario {
    let shape = format!(
        "initial_shape=Some(Polyline((file: \"../knots/imc-der/n{turns}.txt\", cm_per_unit: 100.0)))"
    );
    let set = Override::parse(&shape).expect("an override");
    LoadedScenario::load_with(SCENARIO, &[set]).expect("the scenario")
}

#[test]
fn the_overhand_knots_of_n_turns_are_the_two_two_n_plus_one_torus_knots() {
    for turns in 1..=4 {
        let loaded = overhand(turns);
        let (data, bodies) = posed(&loaded);
        let centres: Vec<DVec3> = (0..bodies).map(|i| data.body_centre(i)).collect();
        let report = analyse_knot(&centres, &KnotOptions::default()).expect("analysed");
        // (t^(2n+1) + 1)/(t + 1): 2n + 1 coefficients alternating 1, −1, …, 1.
        let expected: Vec<i64> = (0..=2 * turns).map(|k| if k % 2 == 0 { 1 } else { -1 }).collect();
        assert_eq!(
            report.knot.polynomial().coefficients(),
            expected,
            "n = {turns}: {}",
            report.knot
        );
        assert!(report.agreement > 0.9, "n = {turns}: agreement {}", report.agreement);
    }
}

#[test]
fn the_bending_joints_lie_on_the_curve() {
    let loaded = overhand(2);
    let Some(InitialShape::Polyline(shape)) = &loaded.scenario.initial_shape else {
        panic!("a polyline shape");
    };
    let curve = shape.curve(loaded.body.length_cm());
    let (data, _) = posed(&loaded);
    let distance = |p: DVec3| {
        curve
            .windows(2)
            .map(|w| {
                let s =
                    ((p - w[0]).dot(w[1] - w[0]) / (w[1] - w[0]).length_squared()).clamp(0.0, 1.0);
                p.distance(w[0].lerp(w[1], s))
            })
            .fold(f64::INFINITY, f64::min)
    };
    let joints = &data.joint_frames;
    for (j, frame) in joints.iter().enumerate().filter(|(j, _)| j % 2 == 1) {
        let off = distance(frame.translation);
        assert!(off < 1e-9, "joint {j} is {off} cm off the curve");
    }
    assert!((shape.length_cm() - 100.0).abs() < 0.01, "the curve is the rod's 1 m");
}

#[test]
fn a_vertex_file_that_is_not_a_curve_is_refused_at_its_file() {
    let dir = std::env::temp_dir().join(format!("hagfish-polyline-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let bad = dir.join("bad.txt");
    std::fs::write(&bad, "0 0 0\n1 oops 0\n").expect("a file");
    let shape = format!("initial_shape=Some(Polyline((file: {:?})))", bad.display().to_string());
    let set = Override::parse(&shape).expect("an override");
    let error = match LoadedScenario::load_with(SCENARIO, &[set]) {
        Ok(_) => panic!("a vertex file that is not a curve is accepted"),
        Err(e) => e.to_string(),
    };
    assert!(error.contains("the initial shape") && error.contains("bad.txt: line 2"), "{error}");
    let _ = std::fs::remove_dir_all(&dir);
}
