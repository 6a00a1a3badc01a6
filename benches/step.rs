//! Whole-step benchmarks of the 100-body hagfish built from `data/hagfish/es103.ron`.
//!
//! `step/unconstrained`: one linearly implicit Euler step (kinematics, CRBA mass matrix,
//! Newton–Euler forces, Cholesky of M̃, solve, integrate) in a bent, moving state.

use criterion::{Criterion, criterion_group, criterion_main};
use hagfish_tree::{Data, State, step_unconstrained};

fn hagfish_state() -> (hagfish_tree::Model, State) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/hagfish/es103.ron");
    let biometrics = hagfish_anatomy::Biometrics::load(path).expect("es103.ron loads");
    let model = biometrics.to_model().expect("es103.ron builds");
    let mut state = State::rest(&model);
    for a in 0..model.dof_count() {
        state.q[a] = 0.2 * (a as f64 * 0.37).sin();
        state.qdot[a] = 0.2 * (a as f64 * 0.91).cos();
    }
    (model, state)
}

fn unconstrained(c: &mut Criterion) {
    let (model, state) = hagfish_state();
    let mut data = Data::new(&model);
    c.bench_function("step/unconstrained", |b| {
        b.iter_batched_ref(
            || state.clone(),
            |s| step_unconstrained(&model, s, 0.01, &mut data).expect("step"),
            criterion::BatchSize::SmallInput,
        )
    });
}

criterion_group!(benches, unconstrained);
criterion_main!(benches);
