//! Closed knots from formulas and braid words have the intended polynomial; cut open, with
//! protruding ends and noise, in cm and in m, they are still recognised.

use glam::DVec3;
use hagfish_knots::{KnotOptions, KnotType, analyse_knot, closed_polygon_polynomial};

use crate::curves::{Noise, braid_closure, closed_figure_eight, closed_trefoil, cut_open};

/// 5₂ as the closure of σ₁³σ₂σ₁⁻¹σ₂ (KnotInfo braid notation {1,1,1,2,-1,2}).
fn three_twist() -> Vec<DVec3> {
    braid_closure(&[1, 1, 1, 2, -1, 2], 3, 10)
}

/// 6₂ as the closure of σ₁³σ₂⁻¹σ₁σ₂⁻¹ (KnotInfo {1,1,1,-2,1,-2}).
fn knot_6_2() -> Vec<DVec3> {
    braid_closure(&[1, 1, 1, -2, 1, -2], 3, 10)
}

/// A closed test knot with its expected type, determinant and polynomial.
struct Case {
    name: &'static str,
    curve: Vec<DVec3>,
    knot: KnotType,
    determinant: u64,
    coefficients: &'static [i64],
}

/// Every closed test knot.
fn table() -> Vec<Case> {
    let case = |name, curve, knot, determinant, coefficients| Case {
        name,
        curve,
        knot,
        determinant,
        coefficients,
    };
    vec![
        case("trefoil formula", closed_trefoil(), KnotType::Trefoil, 3, &[1, -1, 1]),
        case("figure-eight formula", closed_figure_eight(), KnotType::FigureEight, 5, &[1, -3, 1]),
        case(
            "4_1 = (σ1σ2⁻¹)²",
            braid_closure(&[1, -2, 1, -2], 3, 12),
            KnotType::FigureEight,
            5,
            &[1, -3, 1],
        ),
        case(
            "5_1 = σ1⁵",
            braid_closure(&[1; 5], 2, 12),
            KnotType::Cinquefoil,
            5,
            &[1, -1, 1, -1, 1],
        ),
        case("5_2 braid", three_twist(), KnotType::ThreeTwist, 7, &[2, -3, 2]),
        case(
            "6_1 = σ1²σ2σ1⁻¹σ3⁻¹σ2σ3⁻¹",
            braid_closure(&[1, 1, 2, -1, -3, 2, -3], 4, 10),
            KnotType::Stevedore,
            9,
            &[2, -5, 2],
        ),
        case("6_2 braid", knot_6_2(), KnotType::Knot6_2, 11, &[1, -3, 3, -3, 1]),
        case(
            "6_3 = σ1²σ2⁻¹σ1σ2⁻²",
            braid_closure(&[1, 1, -2, 1, -2, -2], 3, 10),
            KnotType::Knot6_3,
            13,
            &[1, -3, 5, -3, 1],
        ),
    ]
}

#[test]
fn closed_test_knots_have_the_intended_polynomial_and_determinant() {
    for Case { name, curve, knot, determinant, coefficients } in table() {
        let polynomial = closed_polygon_polynomial(&curve).expect(name);
        assert_eq!(polynomial.coefficients(), coefficients, "{name}");
        assert_eq!(polynomial.determinant(), determinant, "{name}");
        assert_eq!(KnotType::from_polynomial(&polynomial), knot, "{name}");
    }
}

#[test]
fn cut_open_noisy_knots_are_labelled_in_cm_and_in_m() {
    let cases = [
        ("trefoil", closed_trefoil(), KnotType::Trefoil, 120),
        ("figure-eight", closed_figure_eight(), KnotType::FigureEight, 160),
        ("5_2", three_twist(), KnotType::ThreeTwist, 200),
        ("6_2", knot_6_2(), KnotType::Knot6_2, 280),
    ];
    let options = KnotOptions { extent: false, ..KnotOptions::default() };
    let mut noise = Noise::new(7);
    for (name, closed, knot, samples) in cases {
        for scale in [1.0, 0.01] {
            let open = cut_open(&closed, samples, &mut noise, scale);
            let report = analyse_knot(&open, &options).expect(name);
            assert_eq!(report.knot, knot, "{name} at scale {scale}: {report:?}");
            assert!(report.agreement >= 0.9, "{name} at scale {scale}: {report:?}");
            assert_eq!(report.directions_evaluated, options.directions, "{name}");
        }
    }
}
