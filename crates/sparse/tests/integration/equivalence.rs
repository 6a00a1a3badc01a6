//! The tree-structured factor against the dense reduced path on random trees (chains and
//! branching trees, all joint kinds, random states and implicit dampers): the same `M̃x`,
//! the same `M̃⁻¹f`, a split `M̃⁻¹ = L⁻ᵀL⁻¹` whose two passes are transposes, and the same
//! constrained answer (q̇, λ) from the solver with random equality and inequality rows.

use faer::MatMut;
use glam::{DMat3, DVec3};
use hagfish_solver::{
    FactoredMass, Problem, QpBackend, RowKind, RowSource, RowTag, Rows, SolverError, SolverOptions,
    SolverWorkspace,
};
use hagfish_sparse::{SparseError, TreeFactor};
use hagfish_tree::{
    BodySpec, Data, DofParams, JointKind, Model, ModelBuilder, RigidInertia, Transform,
    effective_mass, factor_effective_mass, forward_kinematics, solve_unconstrained,
};
use proptest::prelude::*;

/// Per body: (parent choice, joint code, length, mass, tilt). The parent is
/// `choice % i` for body i > 0 (a random tree), or `i − 1` when `chain`.
pub(crate) type TreeSpec = Vec<(usize, u8, f64, f64, f64)>;

pub(crate) fn tree_spec(max: usize) -> impl Strategy<Value = TreeSpec> {
    prop::collection::vec((0usize..1000, 0u8..5, 0.2f64..1.5, 0.1f64..3.0, -0.6f64..0.6), 1..=max)
}

pub(crate) fn build(spec: &TreeSpec, chain: bool, damping: f64, stiffness: f64) -> Model {
    let mut builder = ModelBuilder::new().gravity(DVec3::new(0.0, 0.0, -980.0));
    for (i, &(choice, code, length, mass, tilt)) in spec.iter().enumerate() {
        let parent = match i {
            0 => None,
            _ if chain => Some(i - 1),
            _ => Some(choice % i),
        };
        let joint = match code {
            0 => JointKind::Revolute { axis: DVec3::X },
            1 => JointKind::UniversalYz,
            2 => JointKind::Revolute { axis: DVec3::new(tilt, 1.0, 0.3).normalize() },
            3 => JointKind::Translation,
            _ => JointKind::Fixed,
        };
        let radius = 0.3 + 0.2 * tilt.abs();
        let transverse = mass * (3.0 * radius * radius + length * length) / 12.0;
        builder.add_body(BodySpec {
            parent,
            joint,
            joint_offset: Transform {
                rotation: DMat3::from_axis_angle(DVec3::new(0.0, 1.0, 1.0).normalize(), tilt),
                translation: DVec3::new(if i == 0 { 0.0 } else { length }, 0.1 * tilt, 0.0),
            },
            body_offset: Transform::from_translation(DVec3::new(length / 2.0, 0.0, 0.0)),
            mass,
            principal_inertia: DVec3::new(0.5 * mass * radius * radius, transverse, transverse),
            radius,
            length,
            skin: None,
            dofs: vec![DofParams { stiffness, damping, ..DofParams::default() }; joint.dof_count()],
        });
    }
    builder.build().expect("valid random tree")
}

pub(crate) fn values(seed: u64, n: usize, scale: f64) -> Vec<f64> {
    (0..n).map(|a| scale * ((a as f64 + 1.0) * 0.731 + seed as f64 * 0.377).sin()).collect()
}

/// Kinematics at a random state with dampers on some bodies and servos on some joints; the dense `M̃` and its factor
/// in `data`, the tree factor assembled and factored.
pub(crate) fn setup(model: &Model, seed: u64, h: f64) -> Result<(Data, TreeFactor), SparseError> {
    let n = model.dof_count();
    let mut data = Data::new(model);
    forward_kinematics(model, &values(seed, n, 1.2), &values(seed + 7, n, 3.0), &mut data);
    data.clear_applied();
    for body in (0..model.body_count()).step_by(3) {
        let x = data.body_centre(body) + DVec3::new(0.1, -0.2, 0.05);
        data.apply_point_damping(body, x, 0.5 + body as f64);
    }
    for a in (0..n).step_by(2) {
        data.servo_stiffness[a] = 40.0 + a as f64;
        data.servo_damping[a] = 0.3;
    }
    effective_mass(model, &mut data, h);
    factor_effective_mass(&mut data, 0.0).expect("dense M̃ is SPD");
    let mut factor = TreeFactor::new(model)?;
    factor.assemble(model, &data, h);
    factor.factor().expect("the tree factor of an SPD M̃");
    Ok((data, factor))
}

pub(crate) fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    let diff: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt();
    let norm: f64 = b.iter().map(|y| y * y).sum::<f64>().sqrt();
    diff / norm.max(1e-300)
}

fn column(x: &mut [f64]) -> MatMut<'_, f64> {
    let n = x.len();
    MatMut::from_column_major_slice_mut(x, n, 1)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn product_and_solve_match_the_dense_path(
        spec in tree_spec(14),
        chain in any::<bool>(),
        seed in 0u64..1000,
        damping in 0.0f64..1.0,
        stiffness in 0.0f64..10.0,
    ) {
        let model = build(&spec, chain, damping, stiffness);
        let n = model.dof_count();
        prop_assume!(n > 0);
        let (mut data, factor) = setup(&model, seed, 0.01).expect("tree factor");
        prop_assert!(factor.is_factored());
        let x = values(seed + 3, n, 2.0);
        let mut dense = vec![0.0; n];
        for (a, out) in dense.iter_mut().enumerate() {
            *out = (0..n).map(|b| data.effective_mass[(a, b)] * x[b]).sum();
        }
        let mut sparse = vec![0.0; n];
        factor.apply(&x, &mut sparse);
        prop_assert!(relative_error(&sparse, &dense) < 1e-12, "M̃x: {:?} vs {:?}", sparse, dense);

        data.effective_momentum.copy_from_slice(&x);
        solve_unconstrained(&mut data);
        let reference: Vec<f64> = (0..n).map(|a| data.qdot_next[(a, 0)]).collect();
        let mut solved = x.clone();
        factor.solve_lower(column(&mut solved));
        factor.solve_upper(column(&mut solved));
        prop_assert!(relative_error(&solved, &reference) < 1e-9,
            "M̃⁻¹f: {:?} vs {:?}", solved, reference);
    }

    #[test]
    fn the_two_passes_are_transposes(
        spec in tree_spec(10),
        seed in 0u64..1000,
    ) {
        let model = build(&spec, false, 0.1, 1.0);
        let n = model.dof_count();
        prop_assume!(n > 0);
        let (_, factor) = setup(&model, seed, 0.01).expect("tree factor");
        let (x, y) = (values(seed + 1, n, 1.0), values(seed + 2, n, 1.0));
        let mut lower = x.clone();
        factor.solve_lower(column(&mut lower));
        let mut upper = y.clone();
        factor.solve_upper(column(&mut upper));
        // ⟨L⁻¹x, y⟩ = ⟨x, L⁻ᵀy⟩.
        let left: f64 = lower.iter().zip(&y).map(|(a, b)| a * b).sum();
        let right: f64 = x.iter().zip(&upper).map(|(a, b)| a * b).sum();
        prop_assert!((left - right).abs() <= 1e-10 * (1.0 + left.abs()), "{left} vs {right}");
    }
}

/// Columns that vanish from random supports (values of `lower_support`, sorted
/// non-increasing, as the contact-space build passes them): solved in batches, each over the
/// bodies of its support only, they equal the columns solved alone over the whole tree, and
/// their zeros stay zero.
fn supported_columns_match_single_ones(spec: &TreeSpec, chain: bool, seed: u64, m: usize) {
    let model = build(spec, chain, 0.1, 1.0);
    let n = model.dof_count();
    let (_, factor) = setup(&model, seed, 0.01).expect("tree factor");
    let mut support: Vec<usize> = values(seed + 5, m, 1.0)
        .iter()
        .map(|v| factor.lower_support(((v.abs() * (n + 1) as f64) as usize).min(n)).unwrap_or(n))
        .collect();
    support.sort_unstable_by(|a, b| b.cmp(a));
    let mut columns = vec![0.0; n * m];
    for (j, (column, &end)) in columns.chunks_mut(n.max(1)).zip(&support).enumerate() {
        column[..end].copy_from_slice(&values(seed + 13 * j as u64, end, 1.0));
    }
    let mut batched = columns.clone();
    factor.solve_lower_supported(MatMut::from_column_major_slice_mut(&mut batched, n, m), &support);
    for (j, &end) in support.iter().enumerate() {
        let mut single = columns[j * n..(j + 1) * n].to_vec();
        factor.solve_lower(column(&mut single));
        let got = &batched[j * n..(j + 1) * n];
        assert_eq!(got, &single[..], "column {j} of {m}, support {end} of {n}");
        assert!(got[end..].iter().all(|&y| y == 0.0), "column {j}: zeros kept");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn supported_batches_solve_like_single_columns(
        spec in tree_spec(14),
        chain in any::<bool>(),
        seed in 0u64..1000,
        m in 0usize..11,
    ) {
        supported_columns_match_single_ones(&spec, chain, seed, m);
    }
}

/// Random feasible rows over `n` DOFs: one equality on DOF 0, then `count` inequalities
/// with coefficients in [−1, 1], all satisfied by a random point q* with slacks in [0, 1]
/// (so the problem is feasible; the ones the unconstrained answer violates become active).
fn random_rows(n: usize, count: usize, seed: u64) -> Rows {
    let feasible = values(seed + 17, n, 2.0);
    let mut rows = Rows::new(n);
    let mut unit = vec![0.0; n];
    unit[0] = 1.0;
    rows.push(RowKind::Equality, RowSource::new(RowTag::new(0), 0), feasible[0], &unit)
        .expect("row");
    for i in 0..count {
        let row = values(seed + 11 * i as u64 + 5, n, 1.0);
        let slack = 0.5 + 0.5 * ((seed + i as u64) as f64 * 1.37).sin();
        let rhs = row.iter().zip(&feasible).map(|(c, q)| c * q).sum::<f64>() - slack;
        rows.push(RowKind::Inequality, RowSource::new(RowTag::new(1), 0), rhs, &row).expect("row");
    }
    rows
}

/// Solves with the dense M̃ and with the tree factor as the operator; (q̇, λ) of each.
fn solve_both(
    data: &Data,
    factor: &TreeFactor,
    force: &[f64],
    rows: &Rows,
    backend: QpBackend,
) -> [(Vec<f64>, Vec<f64>); 2] {
    let options = SolverOptions { backend, ..SolverOptions::default() };
    let dense = Problem::new(data.effective_mass.as_ref(), force, rows).expect("dense problem");
    let operator = Problem::with_operator(factor, force, rows).expect("operator problem");
    [dense, operator].map(|problem| {
        let mut workspace = SolverWorkspace::new(options);
        let report = *workspace.solve(&problem).expect("solve");
        assert!(report.status.is_solved(), "{report:?}");
        (workspace.velocity().to_vec(), workspace.multipliers().to_vec())
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn constrained_solves_match_the_dense_path(
        spec in tree_spec(12),
        chain in any::<bool>(),
        seed in 0u64..1000,
        count in 0usize..8,
    ) {
        let model = build(&spec, chain, 0.1, 1.0);
        let n = model.dof_count();
        prop_assume!(n > 1);
        let (data, factor) = setup(&model, seed, 0.01).expect("tree factor");
        let rows = random_rows(n, count.min(n - 1), seed);
        let force = values(seed + 9, n, 3.0);
        let [dense, sparse] = solve_both(&data, &factor, &force, &rows, QpBackend::ContactSpace);
        prop_assert!(relative_error(&sparse.0, &dense.0) < 1e-9, "q̇ {:?} vs {:?}", sparse.0, dense.0);
        prop_assert!(relative_error(&sparse.1, &dense.1) < 1e-8, "λ {:?} vs {:?}", sparse.1, dense.1);
    }
}

#[test]
fn clarabel_takes_the_operator_too() -> Result<(), SparseError> {
    let spec: TreeSpec =
        (0..8).map(|i| (i * 5, (i % 3) as u8, 0.5, 1.0, 0.05 * i as f64)).collect();
    let model = build(&spec, false, 0.1, 1.0);
    let n = model.dof_count();
    let (data, factor) = setup(&model, 3, 0.01)?;
    let rows = random_rows(n, 4, 3);
    let force = values(4, n, 3.0);
    let [dense, sparse] = solve_both(&data, &factor, &force, &rows, QpBackend::Clarabel);
    assert!(relative_error(&sparse.0, &dense.0) < 1e-6, "{:?} vs {:?}", sparse.0, dense.0);
    let [reference, _] = solve_both(&data, &factor, &force, &rows, QpBackend::ContactSpace);
    assert!(reference.1[1..].iter().any(|l| *l > 1e-6), "some inequality is active");
    assert!(relative_error(&sparse.0, &reference.0) < 1e-5, "clarabel vs contact space");
    Ok(())
}

#[test]
fn several_columns_solve_like_one() -> Result<(), SparseError> {
    let spec: TreeSpec = (0..9).map(|i| (i * 7, (i % 3) as u8, 0.4, 0.8, 0.1 * i as f64)).collect();
    let model = build(&spec, true, 0.1, 1.0);
    let n = model.dof_count();
    let (_, factor) = setup(&model, 5, 0.01)?;
    let (a, b) = (values(1, n, 1.0), values(2, n, 1.0));
    let mut both: Vec<f64> = a.iter().chain(&b).copied().collect();
    factor.solve_lower(MatMut::from_column_major_slice_mut(&mut both, n, 2));
    let mut single = b.clone();
    factor.solve_lower(column(&mut single));
    assert_eq!(&both[n..], &single[..]);
    assert!(relative_error(&both[..n], &single) > 1e-3, "the columns differ");
    Ok(())
}

#[test]
fn a_massless_direction_is_not_positive_definite() -> Result<(), SparseError> {
    // A revolute joint with no damping and no stiffness on a body whose inertia is zeroed
    // after the kinematics (a valid model cannot have one): its pivot is zero.
    let mut builder = ModelBuilder::new();
    builder.add_body(BodySpec {
        parent: None,
        joint: JointKind::Revolute { axis: DVec3::X },
        joint_offset: Transform::IDENTITY,
        body_offset: Transform::IDENTITY,
        mass: 1.0,
        principal_inertia: DVec3::new(0.5, 1.0, 1.0),
        radius: 0.1,
        length: 1.0,
        skin: None,
        dofs: vec![DofParams { stiffness: 0.0, damping: 0.0, ..DofParams::default() }],
    });
    let model = builder.build().expect("valid rod");
    let mut data = Data::new(&model);
    forward_kinematics(&model, &[0.0], &[0.0], &mut data);
    data.inertias[0] = RigidInertia::ZERO;
    let mut factor = TreeFactor::new(&model)?;
    factor.assemble(&model, &data, 0.01);
    let result = factor.factor();
    assert_eq!(result, Err(SolverError::NotPositiveDefinite { pivot: 0 }));
    assert!(!factor.is_factored());
    Ok(())
}
