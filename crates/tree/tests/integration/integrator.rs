//! The linearly implicit Euler step against analytic and independent references: a single
//! pendulum's small-angle period, a double pendulum against textbook Lagrange equations
//! integrated by RK4, energy and momentum drift of a free chain (first order in h), energy
//! decay with damping, and bitwise determinism.

use crate::common::*;
use glam::{DMat3, DVec3};
use hagfish_tree::{Data, DofParams, JointKind, Model, ModelBuilder, State, Transform};
use hagfish_tree::{forward_kinematics, mass_matrix, step_unconstrained};

const G: f64 = 980.0;

/// Planar rods hanging along −Y at q = 0, each joint a revolute about +Z, gravity −Y.
fn hanging_rods(rods: &[(f64, f64, f64)]) -> Model {
    let mut builder = ModelBuilder::new().gravity(DVec3::new(0.0, -G, 0.0));
    let mut previous = 0.0;
    for (i, &(mass, length, radius)) in rods.iter().enumerate() {
        let joint_offset = if i == 0 {
            Transform {
                rotation: DMat3::from_rotation_z(-std::f64::consts::FRAC_PI_2),
                translation: DVec3::ZERO,
            }
        } else {
            Transform::from_translation(DVec3::new(previous, 0.0, 0.0))
        };
        let joint = JointKind::Revolute { axis: DVec3::Z };
        let body = Cylinder { mass, length, radius };
        builder.add_body(body.spec(
            i.checked_sub(1),
            joint,
            joint_offset,
            vec![DofParams::default()],
        ));
        previous = length;
    }
    builder.build().expect("valid rods")
}

fn run(
    model: &Model,
    state: &mut State,
    h: f64,
    duration: f64,
    mut each: impl FnMut(&State, &Data),
) {
    let mut data = Data::new(model);
    let steps = (duration / h).round() as usize;
    for _ in 0..steps {
        data.clear_applied();
        step_unconstrained(model, state, h, &mut data).expect("step");
        each(state, &data);
    }
}

/// The complete elliptic integral of the first kind K(k) = π / (2 AGM(1, √(1 − k²))).
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The pendulum's period at amplitude θ₀, exactly: T = 4√(I/(mgd)) K(sin(θ₀/2)) — the small-
/// angle period 2π√(I/(mgd)) is short by θ₀²/16 (6.25e-6 at θ₀ = 0.01 rad), more than the
/// integrator's own error, so the exact period is the reference.
///
/// Gravity is evaluated at the start of the step and q ← q + h q̇¹ uses the new velocity, so for
/// this undamped pendulum the step is symplectic Euler, whose period is long by (ωh)²/24
/// (6.1e-8 at ωh = 1.2e-3); the bound is twice that (the linear interpolation of the zero
/// crossings errs by O(h³): the curve has no curvature where it crosses zero).
#[test]
fn single_pendulum_matches_the_exact_period() {
    let (mass, length, radius) = (2.0, 10.0, 0.5);
    let model = hanging_rods(&[(mass, length, radius)]);
    let d = length / 2.0;
    let pivot_inertia = cylinder_inertia(mass, radius, length).z + mass * d * d;
    let omega = (mass * G * d / pivot_inertia).sqrt();
    let amplitude: f64 = 0.01;
    let period = 4.0 / omega * elliptic_k((0.5 * amplitude).sin());
    let h = 1e-4;
    let mut state = State::rest(&model);
    state.q[0] = amplitude;
    // Upward zero crossings of q, linearly interpolated.
    let mut crossings = Vec::new();
    let mut previous = (state.t, state.q[0]);
    run(&model, &mut state, h, 6.0 * period, |s, _| {
        if previous.1 < 0.0 && s.q[0] >= 0.0 {
            let f = previous.1 / (previous.1 - s.q[0]);
            crossings.push(previous.0 + f * (s.t - previous.0));
        }
        previous = (s.t, s.q[0]);
    });
    assert!(crossings.len() >= 5, "only {} crossings", crossings.len());
    let measured = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let error = (measured - period).abs() / period;
    let bound = 2.0 * (omega * h).powi(2) / 24.0;
    println!(
        "period exact {period:.9} s, simulated {measured:.9} s, relative error {error:.2e} \
         (bound {bound:.2e})"
    );
    assert!(error < bound, "relative period error {error} > {bound}");
}

/// Textbook double pendulum of two rods in absolute angles φ₁, φ₂ from the downward vertical
/// (Lagrange): with a = I₁ + m₁c₁² + m₂l₁², b = I₂ + m₂c₂², c = m₂l₁c₂, Δ = φ₁ − φ₂:
/// a φ̈₁ + c cosΔ φ̈₂ = −c sinΔ φ̇₂² − g(m₁c₁ + m₂l₁) sin φ₁,
/// c cosΔ φ̈₁ + b φ̈₂ = c sinΔ φ̇₁² − g m₂ c₂ sin φ₂.
fn double_pendulum_rk4(
    rods: [(f64, f64, f64); 2],
    start: [f64; 4],
    h: f64,
    duration: f64,
) -> [f64; 4] {
    let [(m1, l1, r1), (m2, l2, r2)] = rods;
    let (c1, c2) = (l1 / 2.0, l2 / 2.0);
    let a = cylinder_inertia(m1, r1, l1).z + m1 * c1 * c1 + m2 * l1 * l1;
    let b = cylinder_inertia(m2, r2, l2).z + m2 * c2 * c2;
    let c = m2 * l1 * c2;
    let rate = |y: [f64; 4]| {
        let [p1, p2, w1, w2] = y;
        let delta = p1 - p2;
        let r1 = -c * delta.sin() * w2 * w2 - G * (m1 * c1 + m2 * l1) * p1.sin();
        let r2 = c * delta.sin() * w1 * w1 - G * m2 * c2 * p2.sin();
        let (m11, m12, m22) = (a, c * delta.cos(), b);
        let det = m11 * m22 - m12 * m12;
        [w1, w2, (m22 * r1 - m12 * r2) / det, (m11 * r2 - m12 * r1) / det]
    };
    let add = |y: [f64; 4], k: [f64; 4], s: f64| std::array::from_fn(|i| y[i] + s * k[i]);
    let mut y = start;
    for _ in 0..(duration / h).round() as usize {
        let k1 = rate(y);
        let k2 = rate(add(y, k1, h / 2.0));
        let k3 = rate(add(y, k2, h / 2.0));
        let k4 = rate(add(y, k3, h));
        y = std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    y
}

#[test]
fn double_pendulum_matches_lagrangian_reference() {
    let rods = [(1.0, 8.0, 0.4), (0.6, 6.0, 0.3)];
    let model = hanging_rods(&rods);
    let (p1, p2) = (0.6, -0.3);
    let duration = 2.0;
    let reference = double_pendulum_rk4(rods, [p1, p2, 0.0, 0.0], 1e-5, duration);
    let error_at = |h: f64| {
        let mut state = State::rest(&model);
        state.q = vec![p1, p2 - p1]; // relative joint angle
        run(&model, &mut state, h, duration, |_, _| {});
        let angles = [state.q[0], state.q[0] + state.q[1]];
        (angles[0] - reference[0]).abs().max((angles[1] - reference[1]).abs())
    };
    let (coarse, fine) = (error_at(2e-5), error_at(1e-5));
    println!(
        "double pendulum max angle error over {duration} s: h=2e-5 {coarse:.3e} rad, h=1e-5 {fine:.3e} rad"
    );
    // First-order method: halving h must roughly halve the error, and the fine error is small.
    assert!(fine < 0.65 * coarse, "not converging at first order: {coarse} → {fine}");
    assert!(fine < 1e-2, "angle error {fine} rad");
}

fn kinetic_energy_and_root_momentum(model: &Model, state: &State) -> (f64, f64) {
    let mut data = Data::new(model);
    forward_kinematics(model, &state.q, &state.qdot, &mut data);
    mass_matrix(model, &mut data);
    let n = model.dof_count();
    let mqdot: Vec<f64> =
        (0..n).map(|a| (0..n).map(|b| data.mass_matrix[(a, b)] * state.qdot[b]).sum()).collect();
    let energy = 0.5 * mqdot.iter().zip(&state.qdot).map(|(p, v)| p * v).sum::<f64>();
    (energy, mqdot[0])
}

fn free_chain(damping: f64) -> (Model, State) {
    let bodies = (0..12).map(|i| ((i % 2) as u8, 0.8, 0.4, 1.0 - 0.03 * i as f64, 0.0)).collect();
    let model = build_chain(&ChainSpec { bodies }, DVec3::ZERO, damping, 0.0);
    let mut state = State::rest(&model);
    for (a, v) in state.qdot.iter_mut().enumerate() {
        *v = 1.5 * ((a as f64) * 0.7).sin();
    }
    (model, state)
}

#[test]
fn free_chain_energy_and_momentum_drift_is_first_order() {
    // Root: a revolute about X anchored at the origin. With no springs, damping or gravity, the
    // kinetic energy and the root DOF's generalized momentum (M q̇)₀ (angular momentum about
    // the X axis) are conserved by the exact flow; the scheme's drift must shrink with h.
    let drift = |h: f64| {
        let (model, mut state) = free_chain(0.0);
        let (e0, p0) = kinetic_energy_and_root_momentum(&model, &state);
        run(&model, &mut state, h, 1.0, |_, _| {});
        let (e1, p1) = kinetic_energy_and_root_momentum(&model, &state);
        ((e1 - e0).abs() / e0, (p1 - p0).abs() / p0.abs().max(1e-12))
    };
    let (energy_coarse, momentum_coarse) = drift(2e-3);
    let (energy_fine, momentum_fine) = drift(1e-3);
    println!(
        "energy drift {energy_coarse:.3e} → {energy_fine:.3e}; momentum drift {momentum_coarse:.3e} → {momentum_fine:.3e}"
    );
    assert!(
        energy_fine < 0.65 * energy_coarse && energy_fine < 0.05,
        "energy drift {energy_coarse} → {energy_fine}"
    );
    assert!(
        momentum_fine < 0.65 * momentum_coarse.max(1e-12) || momentum_fine < 1e-10,
        "momentum drift {momentum_coarse} → {momentum_fine}"
    );
}

/// Damping is dissipative with the right sign: at a step small enough that the scheme's own
/// energy error (first order in h, measured above) is below the damping loss, the kinetic
/// energy never increases, and it ends below the undamped run's. At h = 1e-2 the linearly
/// implicit Euler step does let the kinetic energy rise by up to ~1e-5 relative per step in
/// slow motion and ~1e-2 in violent motion (explicit velocity-product terms); that is recorded
/// in `docs/physics.md`, not hidden here.
#[test]
fn damping_never_increases_kinetic_energy() {
    let h = 1e-4;
    let (model, mut state) = free_chain(0.5);
    let (initial, _) = kinetic_energy_and_root_momentum(&model, &state);
    let mut previous = initial;
    let mut increases = Vec::new();
    run(&model, &mut state, h, 0.5, |s, _| {
        let (energy, _) = kinetic_energy_and_root_momentum(&model, s);
        if energy > previous {
            increases.push((s.t, energy - previous));
        }
        previous = energy;
    });
    assert!(
        increases.is_empty(),
        "kinetic energy increased at {:?}",
        &increases[..increases.len().min(5)]
    );
    let (undamped_model, mut undamped) = free_chain(0.0);
    run(&undamped_model, &mut undamped, h, 0.5, |_, _| {});
    let (undamped_final, _) = kinetic_energy_and_root_momentum(&undamped_model, &undamped);
    println!(
        "kinetic energy after 0.5 s: damped {previous:.4}, undamped {undamped_final:.4}, initial {initial:.4}"
    );
    assert!(previous < 0.995 * undamped_final);
}

#[test]
fn thousand_steps_are_bitwise_deterministic() {
    let bodies = (0..100).map(|i| ((i % 2) as u8, 0.424, 0.8, 0.8, 0.0)).collect();
    let model = build_chain(&ChainSpec { bodies }, DVec3::ZERO, 0.1, 1.0);
    let simulate = || {
        let mut state = State::rest(&model);
        for (a, v) in state.qdot.iter_mut().enumerate() {
            *v = ((a as f64) * 1.3).sin();
        }
        run(&model, &mut state, 1e-2, 10.0, |_, _| {});
        state
    };
    let (a, b) = (simulate(), simulate());
    assert!(a.q.iter().any(|v| v.abs() > 1e-3), "the chain did not move");
    assert!(a.q.iter().zip(&b.q).all(|(x, y)| x.to_bits() == y.to_bits()));
    assert!(a.qdot.iter().zip(&b.qdot).all(|(x, y)| x.to_bits() == y.to_bits()));
}

/// A joint servo (`Data::servo_stiffness`, `Data::servo_damping` and its explicit torque
/// `k(q* − q⁰) + c q̇*`) is the joint's own spring and damper: a chain with springs k and
/// dampers c (rest 0) steps as the same chain without them driven by servos of gains (k, c)
/// toward 0 at rate 0 — even at a stiffness far beyond what an explicit torque could take at
/// this h (k h² / I ≈ 10⁴) — and settles there.
#[test]
fn a_servo_steps_as_the_joints_own_spring_and_damper() {
    let (k, c, h) = (5.0e4, 30.0, 1e-2);
    let bodies = (0..12).map(|i| ((i % 2) as u8, 0.8, 0.4, 1.0 - 0.03 * i as f64, 0.0)).collect();
    let spec = ChainSpec { bodies };
    let with_springs = build_chain(&spec, DVec3::ZERO, c, k);
    let (bare, mut sprung) = free_chain(0.0);
    for (a, q) in sprung.q.iter_mut().enumerate() {
        *q = 0.3 * (a as f64 * 1.3).cos();
    }
    let mut served = sprung.clone();
    let mut spring_data = Data::new(&with_springs);
    let mut servo_data = Data::new(&bare);
    for _ in 0..1000 {
        spring_data.clear_applied();
        step_unconstrained(&with_springs, &mut sprung, h, &mut spring_data).expect("step");
        servo_data.clear_applied();
        for a in 0..bare.dof_count() {
            servo_data.servo_stiffness[a] = k;
            servo_data.servo_damping[a] = c;
            servo_data.applied_torques[a] = -k * served.q[a];
        }
        step_unconstrained(&bare, &mut served, h, &mut servo_data).expect("step");
    }
    let gap = sprung.q.iter().zip(&served.q).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let settled = served.q.iter().map(|q| q.abs()).fold(0.0, f64::max);
    assert!(gap < 1e-9, "servo and spring differ by {gap} rad");
    assert!(settled < 1e-3, "the servos hold the chain at their targets: {settled} rad off");
}
