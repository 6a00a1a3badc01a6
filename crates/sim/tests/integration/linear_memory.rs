//! On the sparse backend the step's memory is linear in the bodies: no buffer is n × n (the
//! dense mass matrices are allocated only by the stages that fill them, the rows and the
//! contact-space matrices are sized by the rows present). Counted by `allocation-counter` on
//! this test's thread: the bytes allocated to build a world of a bent chain and step it 20
//! times at 1000 and at 4000 bodies.

use hagfish_anatomy::segment_chain;
use hagfish_control::Passive;
use hagfish_sim::{DynamicsBackend, StepOptions, World};
use hagfish_tree::State;

/// Bytes allocated to build and step a sparse-backend world of `bodies` bodies, bent so that
/// it moves and meets its joint limits (rows), with the head held.
fn bytes_to_build_and_step(bodies: usize) -> u64 {
    let bytes = allocation_counter::measure(|| {
        let model = segment_chain(bodies).expect("chain");
        let mut state = State::rest(&model);
        for (k, q) in state.q.iter_mut().enumerate() {
            *q = 0.3 * (0.05 * k as f64).sin();
        }
        let options =
            StepOptions { backend: DynamicsBackend::SparseMaximal, ..StepOptions::default() };
        let mut world = World::new(model, options, state).expect("world");
        for _ in 0..20 {
            world.step(&mut Passive).expect("step");
        }
    })
    .bytes_total;
    println!("{bodies} bodies: {:.1} MB allocated", bytes as f64 / 1e6);
    bytes
}

#[test]
fn sparse_memory_grows_linearly_with_the_bodies() {
    let (small, large) = (bytes_to_build_and_step(1000), bytes_to_build_and_step(4000));
    let ratio = large as f64 / small as f64;
    println!("4000 / 1000 bodies: {ratio:.2}");
    assert!(ratio <= 4.5, "allocated bytes grow faster than the bodies: ratio {ratio:.2}");
}
