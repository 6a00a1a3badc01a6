//! Open curves that do not thread through themselves are unknots.

use std::f64::consts::TAU;

use glam::DVec3;
use hagfish_knots::{KnotOptions, KnotType, analyse_knot, closed_polygon_polynomial};

use crate::curves::{Noise, closed_switched_trefoil, cut_open};

/// Asserts that `points` is reported as an unknot with agreement ≥ 0.9 and no extent.
fn assert_unknot(name: &str, points: &[DVec3]) {
    let report = analyse_knot(points, &KnotOptions::default()).expect(name);
    assert_eq!(report.knot, KnotType::Unknot, "{name}: {report:?}");
    assert_eq!(report.determinant, 1, "{name}");
    assert!(report.agreement >= 0.9, "{name}: {report:?}");
    assert_eq!((report.extent, report.position), (None, None), "{name}");
}

#[test]
fn straight_line_is_an_unknot() {
    let line: Vec<DVec3> = (0..100).map(|k| DVec3::new(0.424 * k as f64, 0.0, 0.0)).collect();
    assert_unknot("line", &line);
}

#[test]
fn planar_spiral_and_open_helix_are_unknots() {
    let spiral: Vec<DVec3> = (0..150)
        .map(|k| {
            let angle = 3.0 * TAU * k as f64 / 149.0;
            (1.0 + 0.3 * angle) * DVec3::new(angle.cos(), angle.sin(), 0.0)
        })
        .collect();
    assert_unknot("planar spiral", &spiral);
    let helix: Vec<DVec3> = (0..100)
        .map(|k| {
            let angle = 2.0 * TAU * k as f64 / 99.0;
            DVec3::new(2.0 * angle.cos(), 2.0 * angle.sin(), 0.3 * angle)
        })
        .collect();
    assert_unknot("two-turn helix", &helix);
}

#[test]
fn trefoil_with_one_crossing_switched_is_an_unknot() {
    let closed = closed_switched_trefoil();
    let polynomial = closed_polygon_polynomial(&closed).expect("generic");
    assert_eq!(KnotType::from_polynomial(&polynomial), KnotType::Unknot);
    assert_unknot("switched trefoil, cut open", &cut_open(&closed, 150, &mut Noise::new(3), 1.0));
}
