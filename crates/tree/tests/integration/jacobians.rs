//! Jacobians against central finite differences on random chains (2–100 bodies, both joint
//! kinds and tilted revolutes): body Jacobian J, the velocity product J̇q̇, point Jacobians.

use crate::common::{self, *};
use faer::Mat;
use glam::DVec3;
use hagfish_tree::jacobian::{
    add_point_row, add_point_rows, add_point_rows_along, body_bias_acceleration, body_jacobian,
    body_twist, point_jacobian,
};
use proptest::prelude::*;

const EPS: f64 = 1e-6;
const TOLERANCE: f64 = 1e-6;

fn chain_and_state() -> impl Strategy<Value = (ChainSpec, Vec<f64>, Vec<f64>, usize, [f64; 3])> {
    chain_spec(2, 100).prop_flat_map(|spec| {
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let n = model.dof_count();
        let nb = model.body_count();
        (Just(spec), vector(n, 1.5), vector(n, 2.0), 0..nb, [-1.0f64..1.0, -1.0..1.0, -1.0..1.0])
    })
}

/// One point per scale, on bodies `first`, `first + stride`, … (modulo `bodies`), each offset
/// from its body's centre.
fn spread_points(
    data: &hagfish_tree::Data,
    bodies: usize,
    (first, stride): (usize, usize),
    scales: &[f64],
) -> Vec<(usize, DVec3, f64)> {
    scales
        .iter()
        .enumerate()
        .map(|(k, &scale)| {
            let b = (first + stride * k) % bodies;
            (b, data.body_centre(b) + DVec3::new(0.1 * k as f64, 0.2, -0.1), scale)
        })
        .collect()
}

/// `add_point_rows` against the sum of `add_point_row` over the points, and
/// `add_point_rows_along` three directions against `add_point_rows` along each.
fn check_blended_rows(
    model: &hagfish_tree::Model,
    data: &hagfish_tree::Data,
    points: &[(usize, DVec3, f64)],
    normal: DVec3,
) -> Result<(), TestCaseError> {
    let n = model.dof_count();
    let mut blended = vec![0.0; n];
    add_point_rows(model, data, points, normal, &mut blended);
    let mut single = vec![0.0; n];
    for &(b, x, scale) in points {
        add_point_row(model, data, b, x, normal, scale, &mut single);
    }
    let scale = single.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
    for (a, (x, y)) in blended.iter().zip(&single).enumerate() {
        prop_assert!((x - y).abs() <= 1e-12 * scale, "dof {a}: {x} vs {y}");
    }
    // Along three directions in one walk: each row bit for bit the walk of its own.
    let directions = [normal, normal.cross(DVec3::X) + DVec3::Y, DVec3::new(0.3, -2.0, 0.7)];
    let mut together = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    add_point_rows_along(model, data, points, directions, together.each_mut().map(|r| &mut r[..]));
    for (row, direction) in together.iter().zip(directions) {
        let mut alone = vec![0.0; n];
        add_point_rows(model, data, points, direction, &mut alone);
        prop_assert_eq!(row, &alone, "along {}", direction);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn body_jacobian_matches_finite_differences((spec, q, _qdot, body, _p) in chain_and_state()) {
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let n = model.dof_count();
        let data = kinematics_at(&model, &q, &vec![0.0; n]);
        let mut jac = Mat::<f64>::zeros(6, n);
        body_jacobian(&model, &data, body, jac.as_mut());
        let frame = data.body_frames[body];
        let mut analytic = Vec::new();
        let mut numeric = Vec::new();
        for a in 0..n {
            let mut qp = q.clone();
            let mut qm = q.clone();
            qp[a] += EPS;
            qm[a] -= EPS;
            let fp = kinematics_at(&model, &qp, &vec![0.0; n]).body_frames[body];
            let fm = kinematics_at(&model, &qm, &vec![0.0; n]).body_frames[body];
            let rt = frame.rotation.transpose();
            let omega = common::vee(rt * (fp.rotation - fm.rotation) * (0.5 / EPS));
            let v = rt * (fp.translation - fm.translation) * (0.5 / EPS);
            numeric.extend([omega.x, omega.y, omega.z, v.x, v.y, v.z]);
            analytic.extend((0..6).map(|r| jac[(r, a)]));
        }
        let err = relative_error(&analytic, &numeric);
        prop_assert!(err < TOLERANCE, "relative error {err}");
    }

    #[test]
    fn velocity_product_matches_finite_differences((spec, q, qdot, body, _p) in chain_and_state()) {
        // J̇q̇ = d/dt (J(q) q̇) along q(t) = q + t q̇ with q̇ held fixed.
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let data = kinematics_at(&model, &q, &qdot);
        let analytic = body_bias_acceleration(&data, body);
        let shifted = |sign: f64| {
            let qs: Vec<f64> = q.iter().zip(&qdot).map(|(a, b)| a + sign * EPS * b).collect();
            body_twist(&kinematics_at(&model, &qs, &qdot), body)
        };
        let numeric = (shifted(1.0) - shifted(-1.0)) * (0.5 / EPS);
        let flat = |s: hagfish_tree::Spatial| [s.angular.x, s.angular.y, s.angular.z, s.linear.x, s.linear.y, s.linear.z];
        let err = relative_error(&flat(analytic), &flat(numeric));
        prop_assert!(err < TOLERANCE, "relative error {err}");
    }

    #[test]
    fn point_jacobian_matches_finite_differences((spec, q, _qdot, body, p) in chain_and_state()) {
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let n = model.dof_count();
        let zero = vec![0.0; n];
        let local = DVec3::from_array(p);
        let data = kinematics_at(&model, &q, &zero);
        let x = data.body_frames[body].transform_point(local);
        let mut jac = Mat::<f64>::zeros(3, n);
        point_jacobian(&model, &data, body, x, jac.as_mut());
        let mut analytic = Vec::new();
        let mut numeric = Vec::new();
        for a in 0..n {
            let point = |delta: f64| {
                let mut qs = q.clone();
                qs[a] += delta;
                kinematics_at(&model, &qs, &zero).body_frames[body].transform_point(local)
            };
            let d = (point(EPS) - point(-EPS)) * (0.5 / EPS);
            numeric.extend([d.x, d.y, d.z]);
            analytic.extend((0..3).map(|r| jac[(r, a)]));
        }
        let err = relative_error(&analytic, &numeric);
        prop_assert!(err < TOLERANCE, "relative error {err}");
    }
}

#[test]
fn universal_joint_motion_subspace_matches_closed_form() {
    // crates/tree/src/joint.rs: in the child frame, S = [(sin q₂, cos q₂, 0), (0, 0, 1)].
    let spec = ChainSpec { bodies: vec![(1, 1.0, 0.3, 1.0, 0.0)] };
    let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
    let (q1, q2) = (0.4, -0.9);
    let data = kinematics_at(&model, &[q1, q2], &[0.0, 0.0]);
    let rt = data.joint_frames[0].rotation.transpose();
    let s1 = rt * data.axes[0].angular;
    let s2 = rt * data.axes[1].angular;
    assert!((s1 - DVec3::new(q2.sin(), q2.cos(), 0.0)).length() < 1e-14);
    assert!((s2 - DVec3::Z).length() < 1e-14);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// On branched trees some points hang off the deepest point's path, and the walk may
    /// never meet the lowest-numbered point's body.
    #[test]
    fn blended_point_rows_equal_the_sum_of_single_point_rows_on_trees(
        (spec, parents, q) in tree_and_position(),
        first in 0usize..30,
        scales in proptest::collection::vec(-2.0f64..2.0, 8)
    ) {
        let model = build_tree(&spec, &parents, DVec3::ZERO, 0.0, 0.0);
        let (n, bodies) = (model.dof_count(), model.body_count());
        let data = kinematics_at(&model, &q, &vec![0.0; n]);
        let points = spread_points(&data, bodies, (first, 5), &scales);
        check_blended_rows(&model, &data, &points, DVec3::new(0.3, -0.8, 0.5).normalize())?;
    }

    #[test]
    fn blended_point_rows_equal_the_sum_of_single_point_rows(
        (spec, q, _qdot, body, p) in chain_and_state(),
        scales in proptest::collection::vec(-2.0f64..2.0, 8)
    ) {
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let (n, bodies) = (model.dof_count(), model.body_count());
        let data = kinematics_at(&model, &q, &vec![0.0; n]);
        let normal = DVec3::from(p).normalize_or(DVec3::X);
        let points = spread_points(&data, bodies, (body, 3), &scales);
        check_blended_rows(&model, &data, &points, normal)?;
    }
}
