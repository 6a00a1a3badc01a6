//! A warmed-up workspace solves without touching the heap.
//!
//! What it pins: every buffer of the contact-space pipeline is owned by the workspace and
//! only grows, so solving problems of the same size again (the simulation's steady state)
//! performs no allocation at all — faer's kernels included. Counted by `allocation-counter`
//! on this test's thread, so the tests running alongside do not pollute the count.

use crate::common::{Rng, Shape, random_mass, scenario};
use hagfish_solver::{Problem, SolveStatus, SolverError, SolverWorkspace};

#[test]
fn warm_solves_do_not_allocate() -> Result<(), SolverError> {
    let mut rng = Rng::new(7);
    let shape =
        Shape { dofs: 150, equalities: 3, inequalities: 60, soft: 2, duplicates: 0.1, tight: 0.3 };
    let mass = random_mass(&mut rng, shape.dofs);
    let first = scenario(&mut rng, mass.clone(), shape);
    let second = scenario(&mut rng, mass, shape);
    let first = Problem::new(first.mass.as_ref(), &first.force, &first.rows)?;
    let second = Problem::new(second.mass.as_ref(), &second.force, &second.rows)?;
    let mut workspace = SolverWorkspace::default();
    for problem in [&first, &second] {
        assert_eq!(workspace.solve(problem)?.status, SolveStatus::Solved);
    }
    let mut solved = Ok(());
    let change = allocation_counter::measure(|| {
        solved = [&first, &second, &first]
            .into_iter()
            .try_for_each(|problem| workspace.solve(problem).map(|_| ()));
    });
    solved?;
    assert_eq!(change.count_total, 0, "{change:?}");
    Ok(())
}
