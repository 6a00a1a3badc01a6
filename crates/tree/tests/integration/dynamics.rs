//! Mass matrix and inverse/forward dynamics on random chains: M is symmetric positive definite
//! and equals Jᵀ M_m J; inverse dynamics followed by forward dynamics returns q̈.

use crate::common::*;
use faer::Mat;
use faer::linalg::cholesky::llt;
use faer::linalg::solvers::Solve;
use glam::DVec3;
use hagfish_tree::jacobian::body_jacobian;
use hagfish_tree::{Data, forward_kinematics, inverse_dynamics, mass_matrix};
use proptest::prelude::*;

fn chain_and_motion() -> impl Strategy<Value = (ChainSpec, Vec<f64>, Vec<f64>, Vec<f64>)> {
    chain_spec(2, 100).prop_flat_map(|spec| {
        let n = build_chain(&spec, DVec3::ZERO, 0.0, 0.0).dof_count();
        (Just(spec), vector(n, 1.5), vector(n, 2.0), vector(n, 5.0))
    })
}

/// `M` against `Jᵀ M_m J` summed body by body.
fn check_mass_matrix(model: &hagfish_tree::Model, data: &Data) -> Result<(), TestCaseError> {
    let n = model.dof_count();
    let m = &data.mass_matrix;
    let mut reference = Mat::<f64>::zeros(n, n);
    let mut jac = Mat::<f64>::zeros(6, n);
    for (k, body) in model.bodies().iter().enumerate() {
        body_jacobian(model, data, k, jac.as_mut());
        let i = body.principal_inertia;
        let diag = [i.x, i.y, i.z, body.mass, body.mass, body.mass];
        for a in 0..n {
            for b in 0..n {
                reference[(a, b)] +=
                    (0..6).map(|r| jac[(r, a)] * diag[r] * jac[(r, b)]).sum::<f64>();
            }
        }
    }
    let scale = (0..n).map(|a| m[(a, a)].abs()).fold(0.0, f64::max);
    for a in 0..n {
        for b in 0..n {
            prop_assert_eq!(m[(a, b)], m[(b, a)]);
            prop_assert!(
                (m[(a, b)] - reference[(a, b)]).abs() < 1e-10 * scale,
                "M[{a},{b}] = {} vs JᵀMJ {}",
                m[(a, b)],
                reference[(a, b)]
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// On branched trees the CRBA's column entries are the DOFs on each path to the root only
    /// (its contiguous runs break at every branch): the rest of M must stay zero.
    #[test]
    fn mass_matrix_equals_jt_m_j_on_branched_trees((spec, parents, q) in tree_and_position()) {
        let model = build_tree(&spec, &parents, DVec3::ZERO, 0.0, 0.0);
        for body in 0..model.body_count() {
            let mut on_path: Vec<usize> = model.path_to_root(body).flat_map(|j| j.dofs()).collect();
            on_path.sort_unstable();
            let mut in_runs: Vec<usize> = model.path_dof_runs(body).iter().cloned().flatten().collect();
            in_runs.sort_unstable();
            prop_assert_eq!(in_runs, on_path, "DOF runs of the path from body {}", body);
        }
        let qdot = vec![0.0; model.dof_count()];
        let mut data = kinematics_at(&model, &q, &qdot);
        mass_matrix(&model, &mut data);
        check_mass_matrix(&model, &data)?;
    }

    #[test]
    fn mass_matrix_is_spd_and_equals_jt_m_j((spec, q, qdot, _qddot) in chain_and_motion()) {
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let n = model.dof_count();
        let mut data = kinematics_at(&model, &q, &qdot);
        mass_matrix(&model, &mut data);
        check_mass_matrix(&model, &data)?;
        let m = data.mass_matrix.clone();
        let mut factor = m.clone();
        let mut buffer = faer::dyn_stack::MemBuffer::new(
            llt::factor::cholesky_in_place_scratch::<f64>(n, faer::Par::Seq, Default::default()));
        let ok = llt::factor::cholesky_in_place(factor.as_mut(), Default::default(), faer::Par::Seq,
            faer::dyn_stack::MemStack::new(&mut buffer), Default::default());
        prop_assert!(ok.is_ok(), "Cholesky of M failed: not positive definite");
    }

    /// Inverse dynamics (RNEA) then forward dynamics (CRBA mass matrix + Cholesky) returns q̈.
    ///
    /// The consistency of RNEA and CRBA, which a bug would break by O(1), is checked without
    /// any solve: ‖M q̈ + C − τ‖ ≤ 1e-12 (‖M‖‖q̈‖ + ‖C‖).
    ///
    /// Forward dynamics solves M x = b with b = τ − C, so x − q̈ = M⁻¹ (b − M q̈) plus the
    /// solve's own rounding: the round trip can be no closer than the inverse-dynamics
    /// residual carried through M⁻¹. With gravity that residual is not small relative to
    /// M q̈: the gravity wrenches inside RNEA are up to ≈ 60× the inertial ones and cancel
    /// (in CI a bound of cond(M)·ε, blind to this, failed at cond(M) = 4e5 although the solve
    /// of M x = M q̈ was exact to 6e-13). So the assertion is
    /// ‖x − q̈‖ ≤ 2 ‖b − M q̈‖ / λ_min(M) + 10 (n + 1) ε cond(M) ‖q̈‖,
    /// the second term covering the solve and the rounding of M q̈ itself. Measured:
    /// the error is at most 0.47 of it over 5000 random chains (n = 2…300, cond(M) to 2e8).
    /// The solve alone is checked on the bias-free right-hand side M q̈:
    /// relative error ≤ 10·cond(M)·ε (measured ≤ 1.05×).
    #[test]
    fn inverse_then_forward_dynamics_round_trips((spec, q, qdot, qddot) in chain_and_motion()) {
        let model = build_chain(&spec, DVec3::new(0.0, -980.0, 0.0), 0.0, 0.0);
        let n = model.dof_count();
        let mut data = Data::new(&model);
        forward_kinematics(&model, &q, &qdot, &mut data);
        mass_matrix(&model, &mut data);
        let mut tau = vec![0.0; n];
        inverse_dynamics(&model, &mut data, Some(&qddot), &mut tau);
        let mut bias = vec![0.0; n];
        inverse_dynamics(&model, &mut data, None, &mut bias);
        let m = &data.mass_matrix;
        let predicted: Vec<f64> = (0..n)
            .map(|a| (0..n).map(|b| m[(a, b)] * qddot[b]).sum::<f64>() + bias[a])
            .collect();
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let m_norm = m.norm_l2();
        let scale = m_norm * norm(&qddot) + norm(&bias);
        let consistency: Vec<f64> = predicted.iter().zip(&tau).map(|(p, t)| p - t).collect();
        prop_assert!(norm(&consistency) <= 1e-12 * scale, "‖Mq̈ + C − τ‖ = {}", norm(&consistency));

        let mut rhs = Mat::<f64>::from_fn(n, 1, |a, _| tau[a] - bias[a]);
        let llt = m.llt(faer::Side::Lower).expect("M is SPD");
        llt.solve_in_place(rhs.as_mut());
        let recovered: Vec<f64> = (0..n).map(|a| rhs[(a, 0)]).collect();
        let eigenvalues = m.self_adjoint_eigenvalues(faer::Side::Lower).expect("symmetric");
        let condition = eigenvalues[n - 1] / eigenvalues[0];
        let m_qddot: Vec<f64> = (0..n).map(|a| (0..n).map(|b| m[(a, b)] * qddot[b]).sum::<f64>()).collect();
        let residual: Vec<f64> = (0..n).map(|a| tau[a] - bias[a] - m_qddot[a]).collect();
        let bound = 2.0 * norm(&residual) / eigenvalues[0]
            + 10.0 * (n + 1) as f64 * f64::EPSILON * condition * norm(&qddot);
        let err = norm(&recovered.iter().zip(&qddot).map(|(x, y)| x - y).collect::<Vec<_>>());
        prop_assert!(err <= bound,
            "‖x − q̈‖ = {err:.3e}, bound {bound:.3e} (‖τ − C − M q̈‖ = {:.3e}, cond(M) {condition:.3e})",
            norm(&residual));
        // The solve alone, on a right-hand side M q̈ free of the bias: cond(M)·ε bounds it.
        let mut exact_rhs = Mat::<f64>::from_fn(n, 1, |a, _| m_qddot[a]);
        llt.solve_in_place(exact_rhs.as_mut());
        let solved: Vec<f64> = (0..n).map(|a| exact_rhs[(a, 0)]).collect();
        let solve_err = relative_error(&solved, &qddot);
        prop_assert!(solve_err < 10.0 * condition * f64::EPSILON,
            "solve of M x = M q̈: relative error {solve_err}, cond(M) {condition:.3e}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The velocity-product force from the world-frame Newton–Euler pass equals the
    /// body-coordinate formula of `docs/physics.md`, "Kinematics and dynamics", computed independently from the body
    /// Jacobian: `−C = Jᵀ(f_m − M_m J̇q̇)` with the gyroscopic wrench
    /// `f_m = ad(φ)ᵀ M φ = (−ω × Iω; −ω × m ν)`.
    #[test]
    fn velocity_product_force_matches_body_coordinate_formula((spec, q, qdot, _qddot) in chain_and_motion()) {
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let n = model.dof_count();
        let mut data = kinematics_at(&model, &q, &qdot);
        let mut bias = vec![0.0; n];
        inverse_dynamics(&model, &mut data, None, &mut bias);
        let mut reference = vec![0.0; n];
        let mut jac = Mat::<f64>::zeros(6, n);
        for (k, body) in model.bodies().iter().enumerate() {
            body_jacobian(&model, &data, k, jac.as_mut());
            let twist = hagfish_tree::jacobian::body_twist(&data, k);
            let jdot_qdot = hagfish_tree::jacobian::body_bias_acceleration(&data, k);
            let inertia = body.principal_inertia;
            let (w, v) = (twist.angular, twist.linear);
            let moment = -w.cross(inertia * w) - inertia * jdot_qdot.angular;
            let force = -w.cross(v * body.mass) - jdot_qdot.linear * body.mass;
            let wrench = [moment.x, moment.y, moment.z, force.x, force.y, force.z];
            for a in 0..n {
                reference[a] += (0..6).map(|r| jac[(r, a)] * wrench[r]).sum::<f64>();
            }
        }
        let negated: Vec<f64> = bias.iter().map(|b| -b).collect();
        let err = relative_error(&negated, &reference);
        prop_assert!(err < 1e-9, "relative error {err}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// `M̃ = M + h Σ c PᵀP + hD + h²K` for random point dampers c at random body points, built
    /// by one CRBA pass on augmented inertias, against the dense formula from point Jacobians;
    /// and the O(n) generalized momentum equals `M q̇`.
    #[test]
    fn effective_mass_and_momentum_match_dense_formulas(
        (spec, q, qdot, _qddot) in chain_and_motion(),
        dampers in prop::collection::vec((0usize..100, 0.0f64..5.0, [-1.0f64..1.0, -1.0..1.0, -1.0..1.0]), 0..6),
    ) {
        let h = 0.01;
        let model = build_chain(&spec, DVec3::ZERO, 0.3, 2.0);
        let n = model.dof_count();
        let mut data = kinematics_at(&model, &q, &qdot);
        mass_matrix(&model, &mut data);
        let mut expected = data.mass_matrix.clone();
        let mut jac = Mat::<f64>::zeros(3, n);
        for (body, c, p) in &dampers {
            let body = body % model.body_count();
            let x = data.body_frames[body].transform_point(DVec3::from_array(*p));
            data.apply_point_damping(body, x, *c);
            hagfish_tree::jacobian::point_jacobian(&model, &data, body, x, jac.as_mut());
            for a in 0..n {
                for b in 0..n {
                    expected[(a, b)] += h * c * (0..3).map(|r| jac[(r, a)] * jac[(r, b)]).sum::<f64>();
                }
            }
        }
        for (a, dof) in model.dofs().iter().enumerate() {
            expected[(a, a)] += h * dof.damping + h * h * dof.stiffness;
        }
        hagfish_tree::effective_mass(&model, &mut data, h);
        let scale = (0..n).map(|a| expected[(a, a)].abs()).fold(0.0, f64::max);
        for a in 0..n {
            for b in 0..n {
                prop_assert!((data.effective_mass[(a, b)] - expected[(a, b)]).abs() < 1e-10 * scale);
            }
        }
        hagfish_tree::generalized_momentum(&model, &mut data);
        let m = &data.mass_matrix;
        let mqdot: Vec<f64> = (0..n).map(|a| (0..n).map(|b| m[(a, b)] * qdot[b]).sum()).collect();
        let err = relative_error(&data.momentum, &mqdot);
        prop_assert!(err < 1e-12, "momentum relative error {err}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// After an unconstrained step with gravity, applied forces and implicit dampers, the
    /// wrench each joint transmits, projected on its axes, is the joint's torque in the step:
    /// `τ_ext − K(q − q_rest) − (D + hK) q̇¹`. (The other components are the joint's
    /// constraint force, which this identity cannot see; the rod validation checks them.)
    #[test]
    fn joint_wrenches_project_on_the_axes_as_the_joint_torques(
        (spec, q, qdot, torques) in chain_and_motion(),
        force in prop::array::uniform3(-3.0f64..3.0),
    ) {
        let (stiffness, damping, h) = (2.0, 0.3, 0.01);
        let model = build_chain(&spec, DVec3::new(0.0, -981.0, 0.0), damping, stiffness);
        let mut data = Data::new(&model);
        let mut state = hagfish_tree::State { t: 0.0, q: q.clone(), qdot: qdot.clone() };
        hagfish_tree::forward_kinematics(&model, &state.q, &state.qdot, &mut data);
        data.clear_applied();
        let last = model.body_count() - 1;
        let tip = data.body_centre(last);
        data.apply_point_force(last, tip, DVec3::from_array(force));
        data.apply_point_damping(last, tip, 0.7);
        data.applied_torques.copy_from_slice(&torques);
        hagfish_tree::step_unconstrained(&model, &mut state, h, &mut data).expect("steps");
        let external = vec![hagfish_tree::Spatial::ZERO; model.body_count()];
        let mut wrenches = vec![hagfish_tree::Spatial::ZERO; model.body_count()];
        hagfish_tree::joint_wrenches(&model, &mut data, &qdot, &state.qdot, h, &external, &mut wrenches);
        for (a, dof) in model.dofs().iter().enumerate() {
            let joint = model.dof_joint()[a];
            let projected = data.axes[a].dot(&wrenches[joint]);
            let torque = torques[a] - dof.stiffness * (q[a] - dof.rest)
                - (dof.damping + h * dof.stiffness) * state.qdot[a];
            let scale = 1.0 + wrenches.iter().map(|w| w.linear.length() + w.angular.length()).fold(0.0, f64::max);
            prop_assert!((projected - torque).abs() < 1e-9 * scale,
                "DOF {a}: projected {projected} vs torque {torque}");
        }
    }
}

/// A cart–pendulum built from a translation root (mass m₁, free in x, y, z; it never turns, so
/// its own inertia and centre do not enter) and a rod of
/// mass m₂ hinged about +Z at the cart, its centre at distance ℓ along +X at θ = 0. In closed
/// form, with the rod's centre at ℓ(cos θ, sin θ): M_xx = M_yy = M_zz = m₁ + m₂,
/// M_xθ = −m₂ℓ sin θ, M_yθ = m₂ℓ cos θ, M_θθ = m₂ℓ² + I_zz; under gravity g along −y the
/// bias is C_x = −m₂ℓθ̇² cos θ, C_y = −m₂ℓθ̇² sin θ + (m₁ + m₂)g, C_θ = m₂gℓ cos θ.
#[test]
fn a_pendulum_on_a_translating_cart_has_the_closed_form_dynamics() {
    let (m1, m2, length, radius, g) = (2.0, 0.7, 1.6, 0.1, 980.0);
    let cart = Cylinder { mass: m1, length: 0.5, radius };
    let rod = Cylinder { mass: m2, length: 2.0 * length, radius };
    let mut builder = hagfish_tree::ModelBuilder::new().gravity(DVec3::new(0.0, -g, 0.0));
    let free = vec![hagfish_tree::DofParams::default(); 3];
    let hinge = vec![hagfish_tree::DofParams::default()];
    let identity = hagfish_tree::Transform::IDENTITY;
    builder.add_body(cart.spec(None, hagfish_tree::JointKind::Translation, identity, free));
    let about_z = hagfish_tree::JointKind::Revolute { axis: DVec3::Z };
    builder.add_body(rod.spec(Some(0), about_z, identity, hinge));
    let model = builder.build().expect("cart and pendulum");
    let (theta, rate) = (0.7_f64, 1.3_f64);
    let (q, qdot) = ([0.4, -0.2, 0.3, theta], [0.5, -0.1, 0.2, rate]);
    let mut data = Data::new(&model);
    forward_kinematics(&model, &q, &qdot, &mut data);
    mass_matrix(&model, &mut data);
    let mut bias = vec![0.0; 4];
    inverse_dynamics(&model, &mut data, None, &mut bias);
    let inertia = cylinder_inertia(m2, radius, 2.0 * length).z;
    let (sin, cos) = theta.sin_cos();
    let total = m1 + m2;
    let expected_mass = [
        [total, 0.0, 0.0, -m2 * length * sin],
        [0.0, total, 0.0, m2 * length * cos],
        [0.0, 0.0, total, 0.0],
        [-m2 * length * sin, m2 * length * cos, 0.0, m2 * length * length + inertia],
    ];
    let expected_bias = [
        -m2 * length * rate * rate * cos,
        -m2 * length * rate * rate * sin + total * g,
        0.0,
        m2 * g * length * cos,
    ];
    for (a, row) in expected_mass.iter().enumerate() {
        for (b, want) in row.iter().enumerate() {
            let got = data.mass_matrix[(a, b)];
            assert!((got - want).abs() < 1e-12, "M[{a}][{b}] = {got}, expected {want}");
        }
        assert!((bias[a] - expected_bias[a]).abs() < 1e-9, "C[{a}] = {}", bias[a]);
    }
}
