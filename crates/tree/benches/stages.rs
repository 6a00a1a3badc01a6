//! Per-stage timings of the unconstrained step on a 100-body chain with the hagfish's layout
//! (alternating X-revolute / YZ-universal joints, 0.424 cm bodies, 150 DOFs) in a bent,
//! moving state. The whole-hagfish benchmarks live in the workspace's `benches/`.
//!
//! `scaling/<stage>/<bodies>`: the same stages of the dense reduced path for chains of 100,
//! 200, 400 and 1000 bodies of the same segment length (so 150 to 1500 DOFs).

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use hagfish_tree::*;
use std::hint::black_box;

fn chain(bodies: usize) -> (Model, State) {
    let mut builder = ModelBuilder::new();
    let length = 0.424;
    for i in 0..bodies {
        let joint = if i % 2 == 0 {
            JointKind::Revolute { axis: DVec3::X }
        } else {
            JointKind::UniversalYz
        };
        let (mass, radius) = (0.8, 0.85);
        let transverse = mass * (3.0 * radius * radius + length * length) / 12.0;
        builder.add_body(BodySpec {
            parent: i.checked_sub(1),
            joint,
            joint_offset: Transform::from_translation(DVec3::new(
                if i == 0 { 0.0 } else { length },
                0.0,
                0.0,
            )),
            body_offset: Transform::from_translation(DVec3::new(length / 2.0, 0.0, 0.0)),
            mass,
            principal_inertia: DVec3::new(0.5 * mass * radius * radius, transverse, transverse),
            radius,
            length,
            skin: None,
            dofs: vec![
                DofParams { stiffness: 1.0, damping: 0.1, ..DofParams::default() };
                joint.dof_count()
            ],
        });
    }
    let model = builder.build().expect("valid chain");
    let mut state = State::rest(&model);
    for a in 0..model.dof_count() {
        state.q[a] = 0.3 * (a as f64 * 0.37).sin();
        state.qdot[a] = 0.2 * (a as f64 * 0.91).cos();
    }
    (model, state)
}

fn stages(c: &mut Criterion) {
    let (model, state) = chain(100);
    let mut data = Data::new(&model);
    let h = 0.01;
    c.bench_function("tree/forward_kinematics", |b| {
        b.iter(|| forward_kinematics(&model, black_box(&state.q), &state.qdot, &mut data))
    });
    c.bench_function("tree/mass_matrix", |b| b.iter(|| mass_matrix(&model, &mut data)));
    c.bench_function("tree/generalized_force", |b| {
        b.iter(|| generalized_force(&model, black_box(&state.q), &mut data))
    });
    c.bench_function("tree/effective_mass", |b| b.iter(|| effective_mass(&model, &mut data, h)));
    c.bench_function("tree/generalized_momentum", |b| {
        b.iter(|| generalized_momentum(&model, &mut data))
    });
    c.bench_function("tree/factor_effective_mass", |b| {
        b.iter(|| factor_effective_mass(&mut data, 0.0).expect("SPD"))
    });
    c.bench_function("tree/step_unconstrained", |b| {
        b.iter_batched_ref(
            || state.clone(),
            |s| step_unconstrained(&model, s, h, &mut data).expect("step"),
            criterion::BatchSize::SmallInput,
        )
    });
}

fn scaling(c: &mut Criterion) {
    let h = 0.01;
    let mut group = c.benchmark_group("scaling");
    group.sample_size(10);
    for bodies in [100, 200, 400, 1000] {
        let (model, state) = chain(bodies);
        let mut data = Data::new(&model);
        forward_kinematics(&model, &state.q, &state.qdot, &mut data);
        group.bench_function(format!("forward_kinematics/{bodies}"), |b| {
            b.iter(|| forward_kinematics(&model, black_box(&state.q), &state.qdot, &mut data))
        });
        group.bench_function(format!("effective_mass/{bodies}"), |b| {
            b.iter(|| effective_mass(&model, &mut data, h))
        });
        group.bench_function(format!("factor_effective_mass/{bodies}"), |b| {
            b.iter(|| factor_effective_mass(&mut data, 0.0).expect("SPD"))
        });
        group.bench_function(format!("step_unconstrained/{bodies}"), |b| {
            b.iter_batched_ref(
                || state.clone(),
                |s| step_unconstrained(&model, s, h, &mut data).expect("step"),
                criterion::BatchSize::SmallInput,
            )
        });
    }
    group.finish();
}

criterion_group!(benches, stages, scaling);
criterion_main!(benches);
