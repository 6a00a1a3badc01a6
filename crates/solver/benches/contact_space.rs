//! Contact-space QP vs clarabel on a hagfish-sized step: n = 150 (chain mass matrix, diagonal
//! ~0.1 … 5e4), 1 head equality and 60 inequalities of which ~20 (23) end up active.
//!
//! Run: `cargo bench -p hagfish-solver --bench contact_space`. The fast path is timed cold
//! (factor + W + dual QP + recovery + refinement, no warm start) and warm (started from the
//! previous step's multipliers, as in a simulation); clarabel is the reference.

// The tests' problem generators; the bench uses the random rows and numbers only.
#[allow(dead_code)]
#[path = "../tests/integration/common.rs"]
mod common;

use std::hint::black_box;

use common::{Rng, random_row};
use criterion::{Criterion, criterion_group, criterion_main};
use faer::Mat;
use hagfish_solver::{
    Problem, QpBackend, RowKind, RowSource, RowTag, Rows, SolveStatus, SolverOptions,
    SolverWorkspace, WarmStart,
};

/// A hagfish-like chain mass matrix: n hinge joints about one axis, a body of mass 80/n g
/// after each, length 42.4 cm in total; M̃ᵢⱼ = Σ_{k ≥ max(i,j)} (mₖ aₖᵢ aₖⱼ + Iₖ) with lever
/// arms aₖᵢ = (k − i + ½)ℓ, plus h²K + hD = 1e-4 + 1e-3 on the diagonal. Diagonal ~0.1 … 5e4.
fn chain_mass(n: usize) -> Mat<f64> {
    let length = 42.4 / n as f64;
    let mass = 80.0 / n as f64;
    let radius: f64 = 0.85;
    let inertia = mass * (3.0 * radius * radius + length * length) / 12.0;
    Mat::from_fn(n, n, |i, j| {
        let sum: f64 = (i.max(j)..n)
            .map(|k| {
                let arm_i = (k - i) as f64 * length + 0.5 * length;
                let arm_j = (k - j) as f64 * length + 0.5 * length;
                mass * arm_i * arm_j + inertia
            })
            .sum();
        sum + if i == j { 1e-4 + 1e-3 } else { 0.0 }
    })
}

const DOFS: usize = 150;
const INEQUALITIES: usize = 60;
/// Rows violated at the free velocity; 23 of them end up active.
const PUSHING: usize = 30;

/// M̃, f̃ = M̃ q̇⁰ and the rows: a head row e₀ᵀq̇ = q̇*₀ and 60 limit/contact-like rows, all
/// satisfied by a target q̇* near q̇⁰ (so the problem is feasible); `PUSHING` of them are
/// oriented to be violated at q̇⁰ and tight at q̇*, the rest keep a margin at both.
fn hagfish_step() -> (Mat<f64>, Vec<f64>, Rows) {
    let mut rng = Rng::new(2024);
    let mass = chain_mass(DOFS);
    let free: Vec<f64> = (0..DOFS).map(|_| rng.normal()).collect();
    let target: Vec<f64> = free.iter().map(|q| q + 0.5 * rng.normal()).collect();
    let force: Vec<f64> =
        (0..DOFS).map(|i| (0..DOFS).map(|j| mass[(i, j)] * free[j]).sum()).collect();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut rows = Rows::try_with_capacity(DOFS, INEQUALITIES + 1).expect("room for the rows");
    rows.push_zeroed(RowKind::Equality, RowSource::new(RowTag::new(0), 0), target[0])[0] = 1.0;
    for k in 0..INEQUALITIES {
        let mut row = random_row(&mut rng, DOFS);
        if k < PUSHING && dot(&row, &free) > dot(&row, &target) {
            row.iter_mut().for_each(|c| *c = -*c);
        }
        let (at_free, at_target) = (dot(&row, &free), dot(&row, &target));
        let rhs = if k < PUSHING {
            at_target
        } else {
            at_free.min(at_target) - (0.1 + 0.9 * rng.uniform()) * dot(&row, &row).sqrt()
        };
        let source = RowSource::new(RowTag::new(1), k);
        if rows.push(RowKind::Inequality, source, rhs, &row).is_err() {
            unreachable!("rows have n entries");
        }
    }
    (mass, force, rows)
}

fn workspace(backend: QpBackend, warm_start: WarmStart) -> SolverWorkspace {
    SolverWorkspace::new(SolverOptions { backend, warm_start, ..SolverOptions::default() })
}

fn bench(c: &mut Criterion) {
    let (mass, force, rows) = hagfish_step();
    let Ok(problem) = Problem::new(mass.as_ref(), &force, &rows) else {
        unreachable!("the generated problem is well-formed");
    };
    // One solve up front to report the shape of the answer.
    let mut probe = workspace(QpBackend::ContactSpace, WarmStart::Cold);
    if let Ok(report) = probe.solve(&problem) {
        let active: usize = report.active_per_tag.iter().map(|(_, n)| n).sum();
        println!(
            "n = {DOFS}, m = {}, active rows = {active}, {:?} in {} iterations, residual {:e}",
            rows.len(),
            report.status,
            report.iterations,
            report.residuals.worst_relative
        );
        assert_eq!(report.status, SolveStatus::Solved);
    }

    let mut group = c.benchmark_group("contact_space");
    for (name, backend, warm_start) in [
        ("fast_cold", QpBackend::ContactSpace, WarmStart::Cold),
        ("fast_warm", QpBackend::ContactSpace, WarmStart::PreviousMultipliers),
        ("clarabel", QpBackend::Clarabel, WarmStart::Cold),
    ] {
        let mut ws = workspace(backend, warm_start);
        group.bench_function(name, |b| {
            b.iter(|| black_box(ws.solve(black_box(&problem)).map(|r| r.status)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
