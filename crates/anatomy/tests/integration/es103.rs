//! The real ES103 data file: derived masses, radii, limits and the tree layout.

use std::f64::consts::TAU;

use glam::DVec3;
use hagfish_anatomy::{Biometrics, TailTaper, cylinder_inertia};
use hagfish_tree::{JointKind, Transform};

const ES103: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/hagfish/es103.ron");

fn es103() -> Biometrics {
    match Biometrics::load(ES103) {
        Ok(b) => b,
        Err(e) => panic!("{e}"),
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn file_holds_table_6_1_values() {
    let b = es103();
    assert_eq!(b.specimen, "ES103");
    assert_eq!((b.length_cm, b.mass_g, b.body_count), (42.4, 80.0, 100));
    assert_eq!(b.mark_fractions, [0.2, 0.4, 0.6, 0.8]);
    assert_eq!(b.circumferences_cm, [5.6, 5.5, 5.6, 4.3]);
    assert_eq!(b.bending_limits_deg, [21.0, 75.0, 45.0, 51.0]);
    assert_eq!(b.twist_limit_deg, 48.0);
    assert_eq!(b.bending_stiffness_dyn_cm_per_rad, 1.0);
    assert_eq!(b.twist_stiffness_dyn_cm_per_rad, 5.0);
    assert_eq!(b.damping_dyn_cm_s_per_rad, 0.1);
    assert_eq!(b.tail_taper, None);
}

#[test]
fn model_has_100_bodies_150_dofs_and_80_g() -> Result<(), hagfish_anatomy::AnatomyError> {
    let model = es103().to_model()?;
    assert_eq!(model.body_count(), 100);
    assert_eq!(model.dof_count(), 150);
    assert!(close(model.total_mass(), 80.0, 80.0 * 1e-9));
    assert_eq!(model.gravity(), DVec3::ZERO);
    Ok(())
}

#[test]
fn radius_at_marks_is_circumference_over_two_pi() {
    let b = es103();
    for (&u, &c) in b.mark_fractions.iter().zip(&b.circumferences_cm) {
        assert_eq!(b.radius_at(u), c / TAU);
    }
    assert_eq!(b.radius_at(0.0), 5.6 / TAU);
    assert_eq!(b.radius_at(1.0), 4.3 / TAU);
    assert!(close(b.radius_at(0.3), 5.55 / TAU, 1e-12));
}

#[test]
fn body_table_radii_masses_and_density() -> Result<(), hagfish_anatomy::AnatomyError> {
    let b = es103();
    let table = b.body_table()?;
    assert_eq!(table.rows.len(), 100);
    assert_eq!(table.dof_count(), 150);
    assert!(close(table.segment_length_cm, 0.424, 1e-15));
    assert!(close(table.total_mass_g(), 80.0, 80.0 * 1e-9));
    assert!(close(table.density_g_per_cm3, 80.0 / table.volume_cm3, 1e-15));
    assert!(close(table.density_g_per_cm3, 0.871, 0.002), "ρ = {}", table.density_g_per_cm3);
    for row in &table.rows {
        assert_eq!(row.radius_cm, b.radius_at((row.index as f64 + 0.5) / 100.0));
        let volume = std::f64::consts::PI * row.radius_cm.powi(2) * table.segment_length_cm;
        assert!(close(row.mass_g, table.density_g_per_cm3 * volume, 1e-14));
    }
    let (head, tail) = (&table.rows[0], &table.rows[99]);
    assert_eq!(head.radius_cm, 5.6 / TAU);
    assert_eq!(tail.radius_cm, 4.3 / TAU);
    assert!(close(head.mass_g, 0.92, 0.01) && close(tail.mass_g, 0.54, 0.01));
    Ok(())
}

#[test]
fn limits_are_interpolated_at_the_joint() -> Result<(), hagfish_anatomy::AnatomyError> {
    let model = es103().to_model()?;
    // (joint, θ in degrees) worked by hand from θ = 21, 75, 45, 51° at u = 0.2 … 0.8, u = i/100.
    let by_hand = [
        (1, 21.0_f64),
        (19, 21.0),
        (21, 21.0 + 0.05 * 54.0),
        (31, 21.0 + 0.55 * 54.0),
        (41, 75.0 - 0.05 * 30.0),
        (59, 75.0 - 0.95 * 30.0),
        (61, 45.0 + 0.05 * 6.0),
        (99, 51.0),
    ];
    for (joint, theta) in by_hand {
        assert_eq!(model.joints()[joint].kind, JointKind::UniversalYz);
        for k in model.joints()[joint].dofs() {
            let dof = model.dofs()[k];
            assert!(close(dof.upper, theta.to_radians(), 1e-12), "joint {joint}");
            assert!(close(dof.lower, -theta.to_radians(), 1e-12), "joint {joint}");
            assert_eq!((dof.stiffness, dof.damping, dof.rest), (1.0, 0.1, 0.0));
        }
    }
    for joint in (0..100).step_by(2) {
        let j = &model.joints()[joint];
        assert_eq!(j.kind, JointKind::Revolute { axis: DVec3::X });
        let dof = model.dofs()[j.dof_start];
        assert_eq!((dof.lower, dof.upper), ((-48.0f64).to_radians(), 48.0f64.to_radians()));
        assert_eq!((dof.stiffness, dof.damping), (5.0, 0.1));
    }
    Ok(())
}

#[test]
fn chain_layout_follows_redmax_notes() -> Result<(), hagfish_anatomy::AnatomyError> {
    let model = es103().to_model()?;
    let ell = 0.424;
    assert_eq!(model.joints()[0].parent, None);
    assert_eq!(model.joints()[0].offset, Transform::IDENTITY);
    for (i, joint) in model.joints().iter().enumerate().skip(1) {
        assert_eq!(joint.parent, Some(i - 1));
        assert!(close(joint.offset.translation.x, ell, 1e-15));
        assert_eq!(joint.offset.translation.y, 0.0);
    }
    for body in model.bodies() {
        assert!(close(body.offset.translation.x, ell / 2.0, 1e-15));
        assert!(close(body.length, ell, 1e-15));
        assert_eq!(body.principal_inertia, cylinder_inertia(body.mass, body.radius, body.length));
    }
    let head = &model.bodies()[0].principal_inertia;
    assert!(close(head.x, 0.37, 0.01) && close(head.y, 0.20, 0.01));
    Ok(())
}

#[test]
fn build_is_deterministic() -> Result<(), hagfish_anatomy::AnatomyError> {
    let b = es103();
    assert_eq!(b.to_model()?, es103().to_model()?);
    assert_eq!(b.body_table()?, b.body_table()?);
    Ok(())
}

#[test]
fn tail_taper_reaches_tip_radius_and_keeps_mass() -> Result<(), hagfish_anatomy::AnatomyError> {
    let b = Biometrics { tail_taper: Some(TailTaper { tip_radius_cm: 0.3 }), ..es103() };
    assert_eq!(b.radius_at(0.8), 4.3 / TAU);
    assert!(close(b.radius_at(0.9), 0.5 * (4.3 / TAU + 0.3), 1e-12));
    assert_eq!(b.radius_at(1.0), 0.3);
    assert_eq!(b.radius_at(0.5), es103().radius_at(0.5));
    let table = b.body_table()?;
    assert!(close(table.total_mass_g(), 80.0, 80.0 * 1e-9));
    assert!(table.density_g_per_cm3 > es103().body_table()?.density_g_per_cm3);
    Ok(())
}

/// The tip compliance of a chain clamped at the head and bent in one plane by a small tip
/// force: `δ/P = Σ (L − x_j)² / k_j` over the bending DOFs about z at joints x_j (cm/dyn).
fn tip_compliance(model: &hagfish_tree::Model, length: f64) -> f64 {
    let ell = length / model.body_count() as f64;
    model
        .joints()
        .iter()
        .enumerate()
        .filter(|(_, joint)| joint.kind == JointKind::UniversalYz)
        .map(|(i, joint)| {
            let bend_z = &model.dofs()[joint.dofs().end - 1];
            (length - i as f64 * ell).powi(2) / bend_z.stiffness
        })
        .sum()
}

/// The sum of the bending limits (deg) of the joints in the stretch 0.4–0.6 L: the largest
/// bend the chain allows there.
fn bend_allowed_over_a_fifth(fish: &Biometrics) -> Result<f64, hagfish_anatomy::AnatomyError> {
    let table = fish.body_table()?;
    let in_stretch = |r: &&hagfish_anatomy::BodyRow| (0.4..0.6).contains(&r.joint_fraction);
    let universal = |r: &&hagfish_anatomy::BodyRow| r.joint == JointKind::UniversalYz;
    Ok(table.rows.iter().filter(universal).filter(in_stretch).map(|r| r.limits_deg[0].upper).sum())
}

/// D16: the body count is a resolution, not another animal. The bending compliance of the
/// chain is that of the continuous rod `B = k·2ℓ` of the 100-body chain up to the midpoint
/// rule's `−1/N²` (unscaled per-joint springs would make it grow ∝ N); the largest bend over
/// 0.4–0.6 L is the 100-body chain's within one joint's limit (unscaled limits: ∝ N), and
/// the damping per length is the same at every N.
#[test]
fn the_body_count_changes_the_resolution_not_the_animal()
-> Result<(), hagfish_anatomy::AnatomyError> {
    let reference = es103();
    let length = reference.length_cm;
    let rod_bending = reference.bending_stiffness_dyn_cm_per_rad * 2.0 * length / 100.0;
    let continuum = length.powi(3) / (3.0 * rod_bending);
    let bend_at_100 = bend_allowed_over_a_fifth(&reference)?;
    for bodies in [50, 100, 200, 400, 1000] {
        let fish = Biometrics { body_count: bodies, ..reference.clone() };
        let model = fish.to_model()?;
        let n = bodies as f64;
        let error = tip_compliance(&model, length) / continuum - 1.0;
        assert!(close(error, -1.0 / (n * n), 1e-12), "{bodies} bodies: compliance error {error}");
        let bend = bend_allowed_over_a_fifth(&fish)?;
        let one_joint = 75.0 * 100.0 / n;
        assert!(close(bend, bend_at_100, one_joint), "{bodies} bodies: {bend}° vs {bend_at_100}°");
        let damping_per_length = model.dofs()[1].damping * 2.0 * length / n;
        assert!(close(damping_per_length, 0.1 * 2.0 * length / 100.0, 1e-15), "{bodies} bodies");
    }
    Ok(())
}
