//! Scaling of the whole step with the number of bodies, per backend
//! (`StepOptions::backend`): chains of 100, 200, 400 and 1000 ES103-like bodies of the same
//! segment length (0.424 cm; alternating X-revolute / YZ-universal joints, ±45° bending and
//! ±48° twist limits, so 150 to 1500 DOFs), in a bent, moving state.
//!
//! - `scaling/unconstrained/<backend>/<bodies>`: kinematics → dynamics → solve → integrate
//!   with no rows (the pipeline's stages; no contact detection, no controller).
//! - `scaling/head/<backend>/<bodies>`: the whole pipeline step with the head rows only
//!   (no self contact, no wall).
//! - `scaling/factor_solve/<bodies>`: the sparse backend's linear algebra alone — assemble
//!   and factor the maximal-coordinate system and solve `M̃x = f` once (`L⁻¹`, then `L⁻ᵀ`),
//!   the quantity the issue quotes for faer's sparse LDLᵀ (refactor + solve).
//! - `scaling/faer_ldlt/<bodies>`: for comparison, faer's general sparse LDLᵀ (the tree
//!   factor's elimination order, symbolic factorisation once) on the same maximal-coordinate saddle-point system
//!   `[Ĩ, 0, Gᵀ; 0, K̃, −Sᵀ; G, −S, −δI]` (δ = 1e-10 makes it quasi-definite, so no pivoting is
//!   needed): numeric refactor + one solve, the values assembled once outside the loop.
//! - `scaling/rows/<backend>/<bodies>`: the whole pipeline step with self contact and the
//!   wall on, in a zigzag state where one bending DOF in 8 bodies sits within the margin of
//!   its limit: head + joint-limit rows on the QP path (the counts are printed).

use criterion::measurement::WallTime;
use criterion::{BatchSize, BenchmarkGroup, Criterion, criterion_group, criterion_main};
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, MatMut, Par, Side};
use glam::DVec3;
use hagfish_anatomy::segment_chain;
use hagfish_control::Passive;
use hagfish_sim::rows::RowGroup;
use hagfish_sim::{DynamicsBackend, StepOptions, World, pipeline};
use hagfish_solver::FactoredMass;
use hagfish_sparse::TreeFactor;
use hagfish_tree::{Data, Model, Spatial, State};
use std::time::Duration;

const BACKENDS: [DynamicsBackend; 2] =
    [DynamicsBackend::DenseReduced, DynamicsBackend::SparseMaximal];

/// Moving and slightly bent (0.2 rad amplitude, or 0.02 rad with `at_limits`); with
/// `at_limits`, the first DOF of every 4th universal joint 1° inside its ±45° limit, in
/// alternating directions (a zigzag that stays clear of itself and of the wall), so that it
/// gets a limit row (within the 2° margin).
fn state(model: &Model, at_limits: bool) -> State {
    let mut state = State::rest(model);
    let amplitude = if at_limits { 0.02 } else { 0.2 };
    for a in 0..model.dof_count() {
        state.q[a] = amplitude * (a as f64 * 0.37).sin();
        state.qdot[a] = 0.2 * (a as f64 * 0.91).cos();
    }
    if at_limits {
        for (k, joint) in model.joints().iter().enumerate().filter(|(k, _)| k % 8 == 1) {
            let sign = if k % 16 == 1 { 1.0 } else { -1.0 };
            state.q[joint.dof_start] = sign * 44f64.to_radians();
        }
    }
    state
}

fn options(backend: DynamicsBackend, rows: bool) -> StepOptions {
    let default = StepOptions::default();
    StepOptions {
        backend,
        self_contact: rows,
        wall: if rows { default.wall } else { None },
        ..default
    }
}

fn bench_factor_solve(group: &mut BenchmarkGroup<'_, WallTime>, model: &Model) {
    let start = state(model, false);
    let mut data = Data::new(model);
    hagfish_tree::forward_kinematics(model, &start.q, &start.qdot, &mut data);
    let mut factor = TreeFactor::new(model).expect("factor");
    let force: Vec<f64> = (0..model.dof_count()).map(|a| (a as f64 * 0.3).sin()).collect();
    let mut x = force.clone();
    group.bench_function(format!("factor_solve/{}", model.body_count()), |b| {
        b.iter(|| {
            factor.assemble(model, &data, 0.01);
            factor.factor().expect("SPD");
            x.copy_from_slice(&force);
            let n = x.len();
            factor.solve_lower(MatMut::from_column_major_slice_mut(&mut x, n, 1));
            factor.solve_upper(MatMut::from_column_major_slice_mut(&mut x, n, 1));
            x[0]
        })
    });
}

/// The saddle-point matrix (upper triangle, CSC) of `model` at `data` and the right-hand side
/// with `force` on the joint-rate block; returns it with the index of each DOF's unknown.
fn saddle_point(
    model: &Model,
    data: &Data,
    force: &[f64],
) -> (SparseColMat<usize, f64>, Vec<f64>, Vec<usize>) {
    const DELTA: f64 = 1e-10;
    let (h, mut triplets, mut offsets) = (0.01, Vec::new(), Vec::new());
    let push = |i: usize, j: usize, value: f64, triplets: &mut Vec<Triplet<usize, usize, f64>>| {
        triplets.push(Triplet::new(i.min(j), i.max(j), value));
    };
    let mut rate_index = vec![0; model.dof_count()];
    // Leaf-to-root body order, (V, q̇, μ) within a body: the elimination order of the tree
    // factor, given to faer as is (AMD's order put tiny −δ pivots first: a 3e-2 error at 100
    // bodies and a breakdown at 1000).
    offsets.resize(model.body_count(), 0);
    let mut next = 0;
    for (k, joint) in model.joints().iter().enumerate().rev() {
        offsets[k] = next;
        next += 12 + joint.dofs().len();
    }
    let mut rhs = vec![0.0; next];
    for (k, joint) in model.joints().iter().enumerate() {
        let (v, q, mu) = (offsets[k], offsets[k] + 6, offsets[k] + 6 + joint.dofs().len());
        let mut inertia = data.inertias[k];
        inertia.add_scaled(&data.applied_damping[k], h);
        for j in 0..6 {
            let mut unit = [0.0; 6];
            unit[j] = 1.0;
            let e = Spatial::new(
                DVec3::new(unit[0], unit[1], unit[2]),
                DVec3::new(unit[3], unit[4], unit[5]),
            );
            let column = inertia.apply(&e);
            let column = [
                column.angular.x,
                column.angular.y,
                column.angular.z,
                column.linear.x,
                column.linear.y,
                column.linear.z,
            ];
            for (i, value) in column.iter().enumerate().take(j + 1) {
                push(v + i, v + j, *value, &mut triplets);
            }
        }
        for (i, a) in joint.dofs().enumerate() {
            let dof = &model.dofs()[a];
            push(q + i, q + i, h * dof.damping + h * h * dof.stiffness, &mut triplets);
            rate_index[a] = q + i;
            rhs[q + i] = force[a];
            let s = data.axes[a];
            let axis = [s.angular.x, s.angular.y, s.angular.z, s.linear.x, s.linear.y, s.linear.z];
            for (r, value) in axis.iter().enumerate() {
                push(q + i, mu + r, -value, &mut triplets);
            }
        }
        for r in 0..6 {
            push(v + r, mu + r, 1.0, &mut triplets);
            if let Some(parent) = joint.parent {
                push(offsets[parent] + r, mu + r, -1.0, &mut triplets);
            }
            push(mu + r, mu + r, -DELTA, &mut triplets);
        }
    }
    let matrix = SparseColMat::try_new_from_triplets(next, next, &triplets).expect("matrix");
    (matrix, rhs, rate_index)
}

fn bench_faer_ldlt(group: &mut BenchmarkGroup<'_, WallTime>, model: &Model) {
    let start = state(model, false);
    let mut data = Data::new(model);
    hagfish_tree::forward_kinematics(model, &start.q, &start.qdot, &mut data);
    let force: Vec<f64> = (0..model.dof_count()).map(|a| (a as f64 * 0.3).sin()).collect();
    let (matrix, rhs, rate_index) = saddle_point(model, &data, &force);
    let symbolic = factorize_symbolic_cholesky(
        matrix.symbolic(),
        Side::Upper,
        SymmetricOrdering::Identity,
        CholeskySymbolicParams::default(),
    )
    .expect("symbolic");
    let mut values = vec![0.0; symbolic.len_val()];
    let mut buffer = MemBuffer::new(StackReq::any_of(&[
        symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
        symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
    ]));
    let mut x = rhs.clone();
    let mut refactor_and_solve = |x: &mut Vec<f64>| {
        let stack = MemStack::new(&mut buffer);
        let factor = symbolic
            .factorize_numeric_ldlt(
                &mut values,
                matrix.as_ref(),
                Side::Upper,
                LdltRegularization::default(),
                Par::Seq,
                stack,
                Default::default(),
            )
            .expect("quasi-definite");
        x.copy_from_slice(&rhs);
        let n = x.len();
        let stack = MemStack::new(&mut buffer);
        factor.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(x, n, 1),
            Par::Seq,
            stack,
        );
    };
    refactor_and_solve(&mut x);
    // The same M̃⁻¹f from the tree factor, to show that both solve the same system.
    let mut factor = TreeFactor::new(model).expect("factor");
    factor.assemble(model, &data, 0.01);
    factor.factor().expect("SPD");
    let mut tree = force.clone();
    let n = tree.len();
    factor.solve_lower(MatMut::from_column_major_slice_mut(&mut tree, n, 1));
    factor.solve_upper(MatMut::from_column_major_slice_mut(&mut tree, n, 1));
    let difference =
        rate_index.iter().zip(&tree).map(|(&i, t)| (x[i] - t).abs()).fold(0.0, f64::max);
    let size = tree.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    println!(
        "faer_ldlt/{}: {} unknowns, {} factor entries, max |q̇_faer − q̇_tree| / max |q̇| = {:e}",
        model.body_count(),
        x.len(),
        symbolic.len_val(),
        difference / size
    );
    group.bench_function(format!("faer_ldlt/{}", model.body_count()), |b| {
        b.iter(|| {
            refactor_and_solve(&mut x);
            x[0]
        })
    });
}

fn scaling(c: &mut Criterion) {
    let mut group = c.benchmark_group("scaling");
    group.sample_size(10).warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(3));
    for bodies in [100, 200, 400, 1000] {
        let model = segment_chain(bodies).expect("chain");
        bench_factor_solve(&mut group, &model);
        bench_faer_ldlt(&mut group, &model);
        for backend in BACKENDS {
            let start = state(&model, false);
            let step_options = options(backend, false);
            let mut data = hagfish_sim::StepData::new(&model, &step_options).expect("data");
            group.bench_function(format!("unconstrained/{backend:?}/{bodies}"), |b| {
                b.iter_batched_ref(
                    || start.clone(),
                    |s| {
                        pipeline::kinematics(&model, s, &mut data);
                        data.tree.clear_applied();
                        pipeline::dynamics(&model, &step_options, s, &mut data);
                        data.rows.clear();
                        pipeline::solve_velocities(&mut data).expect("solve");
                        hagfish_tree::integrate(s, data.solver.velocity(), 0.01).expect("step")
                    },
                    BatchSize::SmallInput,
                )
            });
            for (name, rows) in [("head", false), ("rows", true)] {
                let start = state(&model, rows);
                let options = options(backend, rows);
                let mut world = World::new(model.clone(), options, start.clone()).expect("world");
                let report = *world.step(&mut Passive).expect("warm-up step");
                println!(
                    "{name}/{backend:?}/{bodies}: path {:?}, rows per group {:?}",
                    report.solve.path,
                    RowGroup::values(&report.solve.rows_per_tag)
                );
                group.bench_function(format!("{name}/{backend:?}/{bodies}"), |b| {
                    b.iter_batched(
                        || start.clone(),
                        |s| {
                            world.set_state(s).expect("state");
                            world.step(&mut Passive).expect("step").solve.iterations
                        },
                        BatchSize::SmallInput,
                    )
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, scaling);
criterion_main!(benches);
