//! The contact space's compressed ranges (`hagfish-solver`, `contact_space/compressed_spans.rs`)
//! on the tree factor: rows made of point velocities on random chains, with their breaks
//! promised, are solved as with the dense reduced path and as with the tree factor offering
//! no wrench span (every row of Y_R in the Gram product); a promise that leaves a break out is
//! caught by the residual check and costs nothing in accuracy.

use faer::MatMut;
use glam::DVec3;
use hagfish_solver::{
    FactoredMass, MassOperator, Problem, RowKind, RowSource, RowTag, Rows, SolverOptions,
    SolverWorkspace, WrenchBreaks,
};
use hagfish_sparse::TreeFactor;
use hagfish_tree::jacobian::{add_point_rows, add_point_rows_along};
use hagfish_tree::{Data, Model};
use proptest::prelude::*;

use crate::equivalence::{TreeSpec, build, relative_error, setup, values};

/// The tree factor without its wrench spans: the contact space forms W_R from every row.
#[derive(Debug)]
struct WithoutSpans<'a>(&'a TreeFactor);

impl FactoredMass for WithoutSpans<'_> {
    fn solve_lower(&self, x: MatMut<'_, f64>) {
        self.0.solve_lower(x);
    }

    fn solve_upper(&self, x: MatMut<'_, f64>) {
        self.0.solve_upper(x);
    }

    fn lower_support(&self, end: usize) -> Option<usize> {
        FactoredMass::lower_support(self.0, end)
    }

    fn solve_lower_supported(&self, x: MatMut<'_, f64>, support: &[usize]) {
        self.0.solve_lower_supported(x, support);
    }
}

impl MassOperator for WithoutSpans<'_> {
    fn dofs(&self) -> usize {
        MassOperator::dofs(self.0)
    }

    fn apply(&self, x: &[f64], out: &mut [f64]) {
        MassOperator::apply(self.0, x, out);
    }
}

/// Which breaks the rows promise.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Promise {
    /// Every body carrying a point.
    Right,
    /// The deepest body only: the range below it holds an unpromised break.
    DeepestOnly,
}

/// Contacts between a point on a body in the chain's middle fifth and one in its last fifth
/// (a knot's two strands), each a row of its own or, every third one, a friction pyramid of
/// four edges over three bases; a limit-like row on one DOF of an early body; all feasible at
/// a random point q* (`count` contacts; bodies from `seed`).
fn contact_rows(model: &Model, data: &Data, count: usize, seed: u64, promise: Promise) -> Rows {
    let (n, bodies) = (model.dof_count(), model.body_count());
    let feasible = values(seed + 17, n, 2.0);
    let mut rows = Rows::new(n);
    let end_of = |body: usize| model.joints()[body].dofs().end;
    let source = RowSource::new(RowTag::new(1), 0);
    let pick = |k: u64, from: usize, to: usize| {
        from + ((values(seed + k, 1, 1.0)[0] * 0.5 + 0.5) * (to - from) as f64) as usize
            % (to - from)
    };
    for i in 0..count as u64 {
        let (a, b) =
            (pick(3 * i, 2 * bodies / 5, 3 * bodies / 5), pick(3 * i + 1, 4 * bodies / 5, bodies));
        let offset = DVec3::new(0.1, -0.2, 0.3) * (i as f64 + 1.0).sin();
        let points =
            [(b, data.body_centre(b) + offset, 1.0), (a, data.body_centre(a) - offset, -1.0)];
        let breaks = match promise {
            Promise::Right => WrenchBreaks::new([end_of(a), end_of(b)]),
            Promise::DeepestOnly => WrenchBreaks::new([end_of(b)]),
        }
        .expect("two breaks");
        let v = values(seed + 3 * i + 2, 3, 1.0);
        let normal = DVec3::new(v[0], v[1], v[2] + 0.1).normalize();
        // Feasible at q* with a slack of 0.1 to 0.9 (cm/s).
        let rhs = |direction: DVec3, k: u64| {
            let mut c = vec![0.0; n];
            add_point_rows(model, data, &points, direction, &mut c);
            c.iter().zip(&feasible).map(|(c, q)| c * q).sum::<f64>() - 0.5 - 0.4 * (k as f64).sin()
        };
        if i % 3 == 2 {
            let first = rows.push_bases();
            add_point_rows_along(
                model,
                data,
                &points,
                [DVec3::X, DVec3::Y, DVec3::Z],
                rows.bases_mut(first),
            );
            rows.set_base_breaks(first, breaks);
            for (k, edge) in [DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y].into_iter().enumerate() {
                let direction = normal + 0.3 * edge.cross(normal);
                let b = rhs(direction, i + k as u64);
                rows.push_combination(
                    RowKind::Inequality,
                    source,
                    b,
                    (first, direction.to_array()),
                );
            }
        } else {
            let row = rows.push_zeroed(RowKind::Inequality, source, rhs(normal, i));
            add_point_rows(model, data, &points, normal, row);
            rows.set_breaks(rows.len() - 1, breaks);
        }
    }
    // A limit's row on the first DOF of the body a tenth along, its joint's two breaks.
    let body = (bodies / 10..bodies).find(|&b| !model.joints()[b].dofs().is_empty()).unwrap_or(0);
    let dofs = model.joints()[body].dofs();
    if let Some(dof) = dofs.clone().next() {
        let row = rows.push_zeroed(RowKind::Inequality, source, feasible[dof] - 0.3);
        row[dof] = 1.0;
        rows.set_breaks(rows.len() - 1, WrenchBreaks::new([dofs.start, dofs.end]).expect("two"));
    }
    rows
}

/// (q̇, λ, rows of the Gram product saved) of the contact-space solve with `mass`.
fn solve(mass: &dyn MassOperator, force: &[f64], rows: &Rows) -> (Vec<f64>, Vec<f64>, usize) {
    let problem = Problem::with_operator(mass, force, rows).expect("operator problem");
    let mut workspace = SolverWorkspace::new(SolverOptions::default());
    let report = *workspace.solve(&problem).expect("solve");
    assert!(report.status.is_solved(), "{report:?}");
    (workspace.velocity().to_vec(), workspace.multipliers().to_vec(), report.gram_rows_saved)
}

/// A chain of `bodies` bodies (joint kinds from `codes`: revolute about X, universal,
/// revolute about a tilted axis, translation; 1 to 3 DOFs each), bent by `seed`.
fn chain(bodies: usize, codes: &[u8], seed: u64) -> TreeSpec {
    (0..bodies)
        .map(|i| {
            let v = values(seed + i as u64, 3, 1.0);
            (0, codes[i % codes.len()] % 4, 0.6 + 0.3 * v[0], 1.0 + 0.5 * v[1], 0.5 * v[2])
        })
        .collect()
}

/// Compressed, without spans and dense: the same answer; (saved rows, q̇ and λ gaps).
fn compare(spec: &TreeSpec, count: usize, seed: u64, promise: Promise) -> (usize, f64, f64) {
    let model = build(spec, true, 0.1, 1.0);
    let n = model.dof_count();
    let (data, factor) = setup(&model, seed, 0.01).expect("tree factor");
    let rows = contact_rows(&model, &data, count, seed, promise);
    let force = values(seed + 9, n, 3.0);
    let (qdot, lambda, saved) = solve(&factor, &force, &rows);
    let (qdot_all, lambda_all, none) = solve(&WithoutSpans(&factor), &force, &rows);
    assert_eq!(none, 0, "without spans nothing is compressed");
    let dense = Problem::new(data.effective_mass.as_ref(), &force, &rows).expect("dense problem");
    let mut workspace = SolverWorkspace::new(SolverOptions::default());
    workspace.solve(&dense).expect("dense solve");
    let (qdot_dense, lambda_dense) = (workspace.velocity(), workspace.multipliers());
    let q_gap = relative_error(&qdot, &qdot_all).max(relative_error(&qdot, qdot_dense));
    let l_gap = relative_error(&lambda, &lambda_all).max(relative_error(&lambda, lambda_dense));
    (saved, q_gap, l_gap)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// On random chains of 30 to 70 bodies with 130 to 200 contacts (enough columns to be
    /// compressed), the compressed Gram product gives the answer of every row of Y_R and of
    /// the dense path, promised right or wrong.
    #[test]
    fn compressed_ranges_give_the_answer_of_every_row(
        bodies in 30usize..70,
        codes in prop::collection::vec(0u8..4, 1..5),
        count in 130usize..200,
        seed in 0u64..1000,
        right in any::<bool>(),
    ) {
        let promise = if right { Promise::Right } else { Promise::DeepestOnly };
        let (_, q_gap, l_gap) = compare(&chain(bodies, &codes, seed), count, seed, promise);
        prop_assert!(q_gap < 1e-9, "q̇ off by {q_gap:e}");
        prop_assert!(l_gap < 1e-8, "λ off by {l_gap:e}");
    }
}

/// On a 60-body chain of universal joints with a knot's 150 contacts, the ranges below and
/// between the contact points are compressed (the trunk of 24 bodies alone is 48 DOFs); with
/// a promise that leaves the lower points out, the residual check refuses the compressed
/// product and the plain one is formed, at the same accuracy; with 30 contacts nothing is
/// compressed (too few columns to pay).
#[test]
fn a_knot_s_ranges_are_compressed_and_a_wrong_promise_is_refused() {
    let spec = chain(60, &[1], 4);
    let (saved, q_gap, l_gap) = compare(&spec, 150, 4, Promise::Right);
    assert!(saved >= 48 - 6, "{saved} rows saved");
    assert!(q_gap < 1e-9 && l_gap < 1e-8, "q̇ {q_gap:e}, λ {l_gap:e}");
    let (few, _, _) = compare(&spec, 30, 4, Promise::Right);
    assert_eq!(few, 0, "30 contacts are too few columns to compress");
    let (wrong, q_gap, l_gap) = compare(&spec, 150, 4, Promise::DeepestOnly);
    assert_eq!(wrong, 0, "the product with unpromised breaks is refused");
    assert!(q_gap < 1e-9 && l_gap < 1e-8, "q̇ {q_gap:e}, λ {l_gap:e}");
}
