//! Invalid input is rejected with a `KnotError`, never a panic; output is deterministic.

use glam::DVec3;
use hagfish_knots::{KnotError, KnotOptions, analyse_knot, closed_polygon_polynomial};

use crate::hagfish_curve::hagfish_trefoil;

#[test]
fn too_few_non_finite_and_degenerate_inputs_are_errors() {
    let options = KnotOptions::default();
    let three = [DVec3::ZERO, DVec3::X, DVec3::Y];
    assert_eq!(
        analyse_knot(&three, &options),
        Err(KnotError::TooFewPoints { count: 3, required: 4 })
    );
    let mut with_nan = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    with_nan[2].y = f64::NAN;
    assert!(matches!(
        analyse_knot(&with_nan, &options),
        Err(KnotError::NonFinitePoint { index: 2, .. })
    ));
    assert!(matches!(
        analyse_knot(&[DVec3::ONE; 5], &options),
        Err(KnotError::DegenerateExtent { .. })
    ));
    let huge = [DVec3::splat(-1e308), DVec3::ZERO, DVec3::X, DVec3::splat(1e308)];
    assert!(matches!(analyse_knot(&huge, &options), Err(KnotError::DegenerateExtent { .. })));
    let zero_directions = KnotOptions { directions: 0, ..options };
    assert!(matches!(
        analyse_knot(&hagfish_trefoil().0, &zero_directions),
        Err(KnotError::InvalidOption { name: "directions", .. })
    ));
    assert!(matches!(
        closed_polygon_polynomial(&[DVec3::ZERO, DVec3::X]),
        Err(KnotError::TooFewPoints { count: 2, required: 3 })
    ));
}

#[test]
fn a_curve_through_itself_has_no_generic_projection() {
    // A closed "figure 8" in the plane crosses itself at the origin in 3-D.
    let figure_8: Vec<DVec3> = (0..64)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 64.0;
            DVec3::new(t.sin(), (2.0 * t).sin(), 0.0)
        })
        .collect();
    assert!(matches!(
        closed_polygon_polynomial(&figure_8),
        Err(KnotError::NoGenericProjection { .. })
    ));
}

#[test]
fn reports_are_deterministic() {
    let (points, _) = hagfish_trefoil();
    let options = KnotOptions::default();
    assert_eq!(analyse_knot(&points, &options), analyse_knot(&points, &options));
}

#[test]
fn a_curve_with_more_crossings_than_the_limit_is_refused() {
    // A tight spiral wound back and forth: every projection shows ≈ turns² / 2 crossings.
    let turns = 60;
    let points: Vec<DVec3> = (0..turns * 40)
        .map(|i| {
            let t = i as f64 / 40.0 * std::f64::consts::TAU;
            let radius = 1.0 + 0.5 * (0.37 * t).sin();
            DVec3::new(radius * t.cos(), radius * t.sin(), (1.3 * t).sin())
        })
        .collect();
    assert_eq!(
        analyse_knot(&points, &KnotOptions::default()),
        Err(KnotError::TooManyCrossings { max: hagfish_knots::MAX_CROSSINGS })
    );
}
