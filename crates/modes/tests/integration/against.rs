//! One run's modes against another's ([`Comparison`]): a field against itself, against a field
//! orthogonal to it, against the same wave sampled on another body's DOFs, and the
//! selections that cannot be compared.

use std::f64::consts::PI;

use hagfish_modes::{Comparison, Decomposition, DofKind, Field, KindSelection, ModesError, Pod};

/// The decomposition of F(t, s) = `f(t, s/L)` on `frames` frames over 2 s and `dofs` DOFs
/// spaced evenly along a 40 cm body (at s/L = (j + ½)/dofs), as one kind `kind`.
fn decomposition(
    kind: KindSelection,
    frames: usize,
    dofs: usize,
    f: impl Fn(f64, f64) -> f64,
) -> Decomposition {
    let length = 40.0;
    let arcs: Vec<f64> = (0..dofs).map(|j| length * (j as f64 + 0.5) / dofs as f64).collect();
    let times: Vec<f64> = (0..frames).map(|i| 2.0 * i as f64 / frames as f64).collect();
    let values = times.iter().flat_map(|t| arcs.iter().map(|s| f(*t, s / length))).collect();
    let field = Field::new("test".into(), times, arcs, length, vec![None; frames], values)
        .expect("a field");
    let pod = Pod::of(&field).expect("a POD");
    let one =
        [DofKind::Twist, DofKind::BendY, DofKind::BendZ].into_iter().find(|&k| kind.includes(k));
    let dof_kinds = vec![one.expect("a one-kind selection"); dofs];
    Decomposition { kind, dof_kinds, field, pod, wave: None }
}

/// A field of many modes: standing patterns sin(mπx) with incommensurate time courses.
fn many_modes(t: f64, x: f64) -> f64 {
    (1..=6)
        .map(|m| (m as f64 * PI * x).sin() * (1.3 * m as f64 * t + 0.4 * m as f64).cos() / m as f64)
        .sum()
}

#[test]
fn a_run_against_itself_has_zero_angles_and_captures_its_own_energy() {
    let d = decomposition(KindSelection::BendY, 40, 50, many_modes);
    let c = Comparison::of(&d, &d, 8).expect("a comparison");
    assert_eq!(c.principal_angles_deg.len(), 8);
    assert!(c.principal_angles_deg.iter().all(|a| a.abs() < 1e-9), "{:?}", c.principal_angles_deg);
    assert_eq!(c.own_cumulative, d.pod.cumulative_fractions()[..8]);
    for (captured, own) in c.captured_by_other.iter().zip(&c.own_cumulative) {
        assert!((captured - own).abs() < 1e-12, "{captured} against {own}");
    }
    assert!(
        c.own_cumulative[0] < 0.9 && c.own_cumulative[5] > 1.0 - 1e-12,
        "{:?}",
        c.own_cumulative
    );
    assert_eq!((c.size, c.other_size), ([40, 50], [40, 50]));
}

#[test]
fn a_field_on_another_part_of_the_body_is_at_right_angles_and_captures_nothing() {
    // Head third against tail third: the resampled shapes have disjoint supports.
    let head = decomposition(KindSelection::Twist, 30, 30, |t, x| {
        if x < 1.0 / 3.0 { many_modes(t, 3.0 * x) } else { 0.0 }
    });
    let tail = decomposition(KindSelection::Twist, 30, 30, |t, x| {
        if x > 2.0 / 3.0 { many_modes(t, 3.0 * x - 2.0) } else { 0.0 }
    });
    let c = Comparison::of(&head, &tail, 4).expect("a comparison");
    assert_eq!(c.principal_angles_deg.len(), 4);
    assert!(c.principal_angles_deg.iter().all(|a| (a - 90.0).abs() < 1e-9), "{c:?}");
    assert!(c.captured_by_other.iter().all(|e| e.abs() < 1e-24), "{c:?}");
}

#[test]
fn the_same_wave_on_a_finer_body_spans_nearly_the_same_modes() {
    let wave = |t: f64, x: f64| (2.0 * PI * 3.0 * x - 2.0 * PI * t).cos();
    let coarse = decomposition(KindSelection::BendZ, 50, 50, wave);
    let fine = decomposition(KindSelection::BendZ, 50, 300, wave);
    let c = Comparison::of(&coarse, &fine, 2).expect("a comparison");
    assert!(c.principal_angles_deg.iter().all(|a| *a < 2.0), "{c:?}");
    assert!(c.captured_by_other[1] > 0.99, "{c:?}");
    assert_eq!(c.other_size, [50, 300]);
}

#[test]
fn different_kinds_or_mixed_kinds_cannot_be_compared() {
    let y = decomposition(KindSelection::BendY, 20, 20, many_modes);
    let z = decomposition(KindSelection::BendZ, 20, 20, many_modes);
    assert!(matches!(Comparison::of(&y, &z, 4), Err(ModesError::Incompatible(_))));
    assert!(matches!(Comparison::of(&y, &y, 0), Err(ModesError::Incompatible(_))));
    // Two kinds at each arc length, as `all` and `bend` have.
    let mut both = decomposition(KindSelection::Bend, 20, 20, many_modes);
    both.field.arcs_cm = both.field.arcs_cm.iter().map(|s| (s / 4.0).floor()).collect();
    let error = Comparison::of(&both, &both, 4).expect_err("shared arc lengths");
    assert!(error.to_string().contains("one DOF kind"), "{error}");
}
