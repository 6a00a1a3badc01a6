//! Friction (`pyramid.rs`): the exact cone on the clarabel path and the inscribed pyramid on
//! the contact-space path. A block on a plane solved by hand (stick; slide along a pyramid
//! edge, where both are exact; slide between two edges, where the pyramid's force lies
//! between cos(π/E) and 1 of Coulomb's), and random contacts, where the pyramid's objective
//! lies between the cone's at μ and at μ cos(π/E) as its inscription demands.

use faer::Mat;
use hagfish_solver::{
    FrictionPyramid, Problem, QpBackend, RowKind, RowSource, RowTag, Rows, SolveReport,
    SolveStatus, SolverError, SolverOptions, SolverWorkspace,
};
use proptest::prelude::*;

use crate::common::{Rng, random_mass, random_row};

const NORMAL: RowTag = RowTag::new(1);
const FRICTION: RowTag = RowTag::new(2);

fn solve(
    backend: QpBackend,
    mass: &Mat<f64>,
    force: &[f64],
    rows: &Rows,
) -> Result<(SolveReport, Vec<f64>, Vec<f64>), SolverError> {
    let mut workspace = SolverWorkspace::new(SolverOptions { backend, ..Default::default() });
    let report = *workspace.solve(&Problem::new(mass.as_ref(), force, rows)?)?;
    Ok((report, workspace.velocity().to_vec(), workspace.multipliers().to_vec()))
}

/// One point contact: its normal row, tangent rows and μ (all right-hand sides 0).
struct Contact {
    normal: Vec<f64>,
    tangents: [Vec<f64>; 2],
    coefficient: f64,
}

/// The contacts as cones (a normal row, then two friction rows).
fn cone_rows(n: usize, contacts: &[Contact], gaps: &[f64]) -> Result<Rows, SolverError> {
    let mut rows = Rows::new(n);
    for (c, (contact, gap)) in contacts.iter().zip(gaps).enumerate() {
        let normal = rows.len();
        rows.push(RowKind::Inequality, RowSource::new(NORMAL, c), -gap, &contact.normal)?;
        let kind = RowKind::Friction { normal, coefficient: contact.coefficient };
        for tangent in &contact.tangents {
            rows.push(kind, RowSource::new(FRICTION, c), 0.0, tangent)?;
        }
    }
    Ok(rows)
}

/// The contacts as pyramids of `edges` edges (inequality rows).
fn pyramid_rows(
    n: usize,
    contacts: &[Contact],
    gaps: &[f64],
    edges: usize,
) -> Result<Rows, SolverError> {
    let mut rows = Rows::new(n);
    let mut row = vec![0.0; n];
    for (c, (contact, gap)) in contacts.iter().zip(gaps).enumerate() {
        let pyramid = FrictionPyramid { coefficient: contact.coefficient, edges, first_angle: 0.0 };
        let tangents = [contact.tangents[0].as_slice(), contact.tangents[1].as_slice()];
        for k in 0..edges {
            let rhs =
                pyramid.edge_row(k, (&contact.normal, -gap), (tangents, [0.0, 0.0]), &mut row);
            rows.push(RowKind::Inequality, RowSource::new(NORMAL, c), rhs, &row)?;
        }
    }
    Ok(rows)
}

/// ½q̇ᵀM̃q̇ − f̃ᵀq̇.
fn objective(mass: &Mat<f64>, force: &[f64], qdot: &[f64]) -> f64 {
    let n = qdot.len();
    let mut value = 0.0;
    for i in 0..n {
        for j in 0..n {
            value += 0.5 * qdot[i] * mass[(i, j)] * qdot[j];
        }
        value -= force[i] * qdot[i];
    }
    value
}

/// A block of mass m on the plane y = 0 (velocities (ẋ, ẏ, ż)), pressed by F_n over a step h
/// and pushed along the plane with impulse p (μ = 0.5). The cone's answer by hand: the block
/// sticks while ‖p‖ ≤ μhF_n; otherwise it slides along p̂ at s = (‖p‖ − μhF_n)/(m(1 + μ²)),
/// leaving the plane at μs (the relaxation's normal velocity), with λ_n = hF_n + mμs. The
/// pyramid (E = 8, an edge along ±x) is the cone where the slip runs along an edge, and
/// otherwise lies between the cone at μ cos(π/8) and at μ.
#[test]
fn a_block_on_a_plane_sticks_and_slides_in_the_cone_and_its_pyramid() -> Result<(), SolverError> {
    let (m, h, pressing, mu) = (2.0, 0.01, 100.0, 0.5);
    let mass = Mat::<f64>::from_fn(3, 3, |i, j| if i == j { m } else { 0.0 });
    let block = |mu| Contact {
        normal: vec![0.0, 1.0, 0.0],
        tangents: [vec![1.0, 0.0, 0.0], vec![0.0, 0.0, 1.0]],
        coefficient: mu,
    };
    let cone = cone_rows(3, &[block(mu)], &[0.0])?;
    let pyramid = pyramid_rows(3, &[block(mu)], &[0.0], 8)?;
    let limit = mu * h * pressing;
    let angle_between_edges = std::f64::consts::PI / 8.0;
    for (push, along_edge) in [
        ([0.3, -0.2], true),
        ([0.9, 0.0], true),
        ([0.9 * angle_between_edges.cos(), 0.9 * angle_between_edges.sin()], false),
    ] {
        let force = [push[0], -h * pressing, push[1]];
        let norm = push[0].hypot(push[1]);
        let speed = ((norm - limit) / (m * (1.0 + mu * mu))).max(0.0);
        let expected = [speed * push[0] / norm, mu * speed, speed * push[1] / norm];
        let (report, qdot, lambda) = solve(QpBackend::Clarabel, &mass, &force, &cone)?;
        assert_eq!(report.status, SolveStatus::Solved, "{push:?}");
        for (got, want) in qdot.iter().zip(expected) {
            assert!((got - want).abs() < 1e-7, "cone {push:?}: q̇ {qdot:?}, expected {expected:?}");
        }
        assert!((lambda[0] - (h * pressing + m * mu * speed)).abs() < 1e-7, "λ_n {lambda:?}");
        let (report, fast, beta) = solve(QpBackend::ContactSpace, &mass, &force, &pyramid)?;
        assert_eq!(report.status, SolveStatus::Solved, "{push:?}");
        let (normal, tangent) =
            FrictionPyramid { coefficient: mu, edges: 8, first_angle: 0.0 }.impulse(&beta);
        let force_ratio = tangent[0].hypot(tangent[1]) / (mu * normal);
        if speed == 0.0 || along_edge {
            for (got, want) in fast.iter().zip(expected) {
                assert!(
                    (got - want).abs() < 1e-12,
                    "pyramid {push:?}: q̇ {fast:?}, expected {expected:?}"
                );
            }
        } else {
            // Between two edges: Coulomb's force short by at most 1 − cos(π/8).
            assert!(
                force_ratio > angle_between_edges.cos() - 1e-12 && force_ratio < 1.0,
                "{force_ratio}"
            );
            let sliding = fast[0].hypot(fast[2]);
            assert!(sliding > speed, "less friction, faster slide: {sliding} against {speed}");
        }
    }
    Ok(())
}

/// Malformed friction rows are refused when the problem is built, and the contact-space
/// backend refuses cones.
#[test]
fn friction_rows_are_checked_and_cones_need_the_reference() -> Result<(), SolverError> {
    let mass = Mat::<f64>::identity(2, 2);
    let cases: [(RowKind, RowKind); 4] = [
        (RowKind::Inequality, RowKind::Friction { normal: 0, coefficient: -0.1 }),
        (RowKind::Inequality, RowKind::Friction { normal: 0, coefficient: f64::NAN }),
        (RowKind::Equality, RowKind::Friction { normal: 0, coefficient: 0.1 }),
        (RowKind::Inequality, RowKind::Friction { normal: 7, coefficient: 0.1 }),
    ];
    for (normal, friction) in cases {
        let mut rows = Rows::new(2);
        rows.push(normal, RowSource::new(NORMAL, 0), 0.0, &[0.0, 1.0])?;
        rows.push(friction, RowSource::new(FRICTION, 0), 0.0, &[1.0, 0.0])?;
        let built = Problem::new(mass.as_ref(), &[0.0, -1.0], &rows);
        assert!(matches!(built, Err(SolverError::InvalidFriction { row: 1, .. })), "{built:?}");
    }
    let mut rows = Rows::new(2);
    rows.push(RowKind::Inequality, RowSource::new(NORMAL, 0), 0.0, &[0.0, 1.0])?;
    rows.push(
        RowKind::Friction { normal: 0, coefficient: 0.3 },
        RowSource::new(FRICTION, 0),
        0.0,
        &[1.0, 0.0],
    )?;
    let refused = solve(QpBackend::ContactSpace, &mass, &[0.0, -1.0], &rows);
    assert!(
        matches!(refused, Err(SolverError::FrictionConeNeedsClarabel { row: 1 })),
        "{:?}",
        refused.err()
    );
    Ok(())
}

/// `contacts` random point contacts on n DOFs: a Jacobian J (3 × n, three rows of
/// `random_row`) seen in a random orthonormal frame (n̂, t̂₁, t̂₂), μ in [0.05, 0.5].
fn random_contacts(rng: &mut Rng, n: usize, contacts: usize) -> Vec<Contact> {
    (0..contacts)
        .map(|_| {
            let jacobian: Vec<Vec<f64>> = (0..3).map(|_| random_row(rng, n)).collect();
            let frame = random_frame(rng);
            let row_of = |axis: [f64; 3]| -> Vec<f64> {
                (0..n).map(|j| (0..3).map(|k| axis[k] * jacobian[k][j]).sum()).collect()
            };
            Contact {
                normal: row_of(frame[0]),
                tangents: [row_of(frame[1]), row_of(frame[2])],
                coefficient: 0.05 + 0.45 * rng.uniform(),
            }
        })
        .collect()
}

/// A random orthonormal frame (Gram–Schmidt on three normal vectors).
fn random_frame(rng: &mut Rng) -> [[f64; 3]; 3] {
    let mut frame = [[0.0; 3]; 3];
    for k in 0..3 {
        let mut v = [rng.normal(), rng.normal(), rng.normal()];
        for done in &frame[..k] {
            let along: f64 = (0..3).map(|i| v[i] * done[i]).sum();
            (0..3).for_each(|i| v[i] -= along * done[i]);
        }
        let norm = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        frame[k] = [v[0] / norm, v[1] / norm, v[2] / norm];
    }
    frame
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// On random contacts the pyramid's answer (contact-space, E = 16) is solved to the
    /// acceptance, its impulses lie in the cone, and its objective ½q̇ᵀM̃q̇ − f̃ᵀq̇ lies between
    /// the exact cone's (clarabel) at μ and at μ cos(π/16): the pyramid's velocities satisfy
    /// fewer conditions than the cone's and more than the narrower cone's.
    #[test]
    fn the_pyramid_lies_between_the_cone_and_the_inscribed_cone(
        seed in any::<u64>(), n in 4usize..12, contacts in 1usize..4,
    ) {
        let mut rng = Rng::new(seed);
        let mass = random_mass(&mut rng, n);
        let contacts = random_contacts(&mut rng, n, contacts.min(n / 3).max(1));
        let gaps: Vec<f64> = contacts.iter().map(|_| if rng.uniform() < 0.7 { 0.0 } else { rng.uniform() }).collect();
        let mut force: Vec<f64> = (0..n).map(|_| rng.normal()).collect();
        for contact in &contacts {
            for (f, a) in force.iter_mut().zip(&contact.normal) {
                *f -= 2.0 * a;
            }
        }
        let edges = 16;
        let pyramid = pyramid_rows(n, &contacts, &gaps, edges).expect("pyramid rows");
        let (report, qdot, beta) = solve(QpBackend::ContactSpace, &mass, &force, &pyramid).expect("fast");
        prop_assert_eq!(report.status, SolveStatus::Solved);
        for (c, contact) in contacts.iter().enumerate() {
            let shape = FrictionPyramid { coefficient: contact.coefficient, edges, first_angle: 0.0 };
            let (normal, tangent) = shape.impulse(&beta[c * edges..(c + 1) * edges]);
            prop_assert!(tangent[0].hypot(tangent[1]) <= contact.coefficient * normal * (1.0 + 1e-12) + 1e-15);
        }
        let narrower: Vec<Contact> = contacts.iter().map(|c| Contact {
            normal: c.normal.clone(),
            tangents: c.tangents.clone(),
            coefficient: c.coefficient * (std::f64::consts::PI / edges as f64).cos(),
        }).collect();
        let (wide, qdot_wide, _) = solve(QpBackend::Clarabel, &mass, &force, &cone_rows(n, &contacts, &gaps).expect("cone")).expect("cone");
        let (narrow, qdot_narrow, _) = solve(QpBackend::Clarabel, &mass, &force, &cone_rows(n, &narrower, &gaps).expect("cone")).expect("narrow cone");
        prop_assume!(wide.status == SolveStatus::Solved && narrow.status == SolveStatus::Solved);
        let (j_pyramid, j_wide, j_narrow) = (
            objective(&mass, &force, &qdot),
            objective(&mass, &force, &qdot_wide),
            objective(&mass, &force, &qdot_narrow),
        );
        let slack = 1e-8 * (1.0 + j_wide.abs());
        prop_assert!(j_narrow <= j_pyramid + slack && j_pyramid <= j_wide + slack,
            "objectives: narrow cone {j_narrow:e}, pyramid {j_pyramid:e}, cone {j_wide:e}");
    }
}
