//! The claims of the decomposition on fields whose modes are known exactly.

mod against;

use std::f64::consts::{FRAC_PI_2, PI};

use hagfish_modes::{Field, Pod, WaveFit, captured_energy, principal_angles, uniform_grid};

/// F(t, s) = cos(k s − ω t) on `frames` × `dofs` points spanning whole periods in s and t,
/// with the knot moving at `knot_speed` cm/s.
fn travelling_wave(k: f64, omega: f64, frames: usize, dofs: usize, knot_speed: f64) -> Field {
    let (length, duration) = (2.0 * PI / k * 3.0, 2.0 * PI / omega * 2.0);
    let arcs: Vec<f64> = (0..dofs).map(|j| length * j as f64 / dofs as f64).collect();
    let times: Vec<f64> = (0..frames).map(|i| duration * i as f64 / frames as f64).collect();
    let values: Vec<f64> =
        times.iter().flat_map(|t| arcs.iter().map(move |s| (k * s - omega * t).cos())).collect();
    let knot = times.iter().map(|t| Some(1.0 + knot_speed * t)).collect();
    Field::new("wave".into(), times, arcs, length, knot, values).expect("a field")
}

#[test]
fn a_travelling_wave_is_two_modes_moving_at_omega_over_k() {
    let (k, omega) = (0.7, 2.3);
    let field = travelling_wave(k, omega, 60, 45, 0.5);
    let pod = Pod::of(&field).expect("a POD");
    let cumulative = pod.cumulative_fractions();
    assert!((cumulative[1] - 1.0).abs() < 1e-12, "two modes carry it all: {cumulative:?}");
    assert!(pod.energy_fractions()[2] < 1e-12);
    assert_eq!(pod.modes_for(0.99), 2);
    let wave = WaveFit::of(&pod, &field).expect("a wave fit");
    assert!((wave.phase_speed_cm_s - omega / k).abs() < 1e-9, "{wave:?}");
    assert!((wave.spatial.slope.abs() - k).abs() < 1e-9, "{wave:?}");
    assert!(wave.spatial.r_squared > 1.0 - 1e-12 && wave.temporal.r_squared > 1.0 - 1e-12);
    let knot = wave.knot.expect("the knot moves");
    assert!((knot.slope - 0.5).abs() < 1e-12);
    assert!((wave.speed_ratio.expect("a ratio") - omega / k / 0.5).abs() < 1e-9);
}

#[test]
fn two_patterns_in_place_are_not_a_wave() {
    // F = cos(ω t) on the head half + 0.5 sin(3 ω t) on the tail half: two modes, but the
    // spatial phase is a step (0 on one half, π/2 on the other), not a line.
    let (k, omega) = (0.7, 2.3);
    let wave = travelling_wave(k, omega, 60, 45, 0.0);
    let half = wave.length_cm / 2.0;
    let values = wave.times.iter().flat_map(|t| {
        wave.arcs_cm
            .iter()
            .map(move |s| if *s < half { (omega * t).cos() } else { 0.5 * (3.0 * omega * t).sin() })
    });
    let field = Field { values: values.collect(), ..wave };
    let pod = Pod::of(&field).expect("a POD");
    assert!((pod.cumulative_fractions()[1] - 1.0).abs() < 1e-12);
    let fit = WaveFit::of(&pod, &field).expect("a fit");
    assert!(fit.spatial.r_squared < 0.9, "{fit:?}");
    assert_eq!(fit.speed_ratio, None, "the knot does not move");
}

#[test]
fn principal_angles_are_zero_within_a_span_and_right_angles_across() {
    let grid = uniform_grid(50);
    let sine = |m: f64| grid.iter().map(|x| (m * PI * x).sin()).collect::<Vec<_>>();
    let basis = vec![sine(1.0), sine(2.0), sine(3.0)];
    for angle in principal_angles(&basis, &basis).expect("angles") {
        assert!(angle.abs() < 1e-6, "{angle}");
    }
    // Combinations of the same vectors span the same space.
    let mixed: Vec<Vec<f64>> = vec![
        basis[0].iter().zip(&basis[1]).map(|(a, b)| a + b).collect(),
        basis[2].iter().zip(&basis[1]).map(|(a, b)| a - 2.0 * b).collect(),
    ];
    let angles = principal_angles(&mixed, &basis).expect("angles");
    assert_eq!(angles.len(), 2);
    assert!(angles.iter().all(|a| a.abs() < 1e-6), "{angles:?}");
    // A vector at the last grid point alone, where every sin(mπx) vanishes: orthogonal.
    let mut other = vec![0.0; grid.len()];
    other[grid.len() - 1] = 1.0;
    for angle in principal_angles(&[other], &basis).expect("angles") {
        assert!((angle - FRAC_PI_2).abs() < 1e-6, "{angle}");
    }
    assert!(principal_angles(&basis, &[vec![1.0; 3]]).is_err(), "different grids");
}

#[test]
fn another_basis_captures_the_energy_in_its_span() {
    let field = travelling_wave(0.7, 2.3, 40, 30, 0.0);
    let pod = Pod::of(&field).expect("a POD");
    let at = field.arcs_l();
    let both = captured_energy(&field, &at, &pod.shapes[..2]).expect("captured");
    assert!((both - 1.0).abs() < 1e-12, "{both}");
    let one = captured_energy(&field, &at, &pod.shapes[..1]).expect("captured");
    assert!((one - pod.energy_fractions()[0]).abs() < 1e-12, "{one}");
}
