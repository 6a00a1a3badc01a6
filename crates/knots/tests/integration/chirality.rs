//! Handedness from the knotted core's writhe, checked against the Gauss integral
//! Wr = (1/4π) ∮∮ (r₁ − r₂)·(dr₁ × dr₂)/|r₁ − r₂|³ computed here by a direct double sum: a
//! trefoil and its mirror image get opposite signs, the sign of Wr (positive: right-handed),
//! and an achiral figure-eight gets about 0. The Alexander polynomial is the same for both
//! trefoils.

use glam::DVec3;
use hagfish_knots::{KnotOptions, KnotType, analyse_knot};

/// The (2,3) torus knot ((2 + cos 3t) cos 2t, (2 + cos 3t) sin 2t, z·sin 3t) with z = ±1.
fn torus_trefoil(t: f64, z: f64) -> DVec3 {
    let r = 2.0 + (3.0 * t).cos();
    DVec3::new(r * (2.0 * t).cos(), r * (2.0 * t).sin(), z * (3.0 * t).sin())
}

/// The torus trefoil cut open by a small gap at t = 0, mirrored in z when `mirror`.
fn open_torus_trefoil(mirror: bool) -> Vec<DVec3> {
    let z = if mirror { 1.0 } else { -1.0 };
    (0..300)
        .map(|k| torus_trefoil(0.05 + (std::f64::consts::TAU - 0.1) * k as f64 / 299.0, z))
        .collect()
}

/// The Gauss integral of the closed torus trefoil (`z` as in [`torus_trefoil`]), by the
/// midpoint rule over `n` segments.
fn gauss_writhe(z: f64, n: usize) -> f64 {
    let points: Vec<DVec3> =
        (0..n).map(|k| torus_trefoil(std::f64::consts::TAU * k as f64 / n as f64, z)).collect();
    let segment =
        |k: usize| (points[(k + 1) % n] - points[k], 0.5 * (points[k] + points[(k + 1) % n]));
    let mut sum = 0.0;
    for i in 0..n {
        let (di, mi) = segment(i);
        for j in (0..n).filter(|&j| j != i) {
            let (dj, mj) = segment(j);
            let r = mi - mj;
            sum += r.dot(di.cross(dj)) / r.length().powi(3);
        }
    }
    sum / (4.0 * std::f64::consts::PI)
}

/// The figure-eight knot (2 + cos 2t) cos 3t, (2 + cos 2t) sin 3t, sin 4t, cut open.
fn open_figure_eight() -> Vec<DVec3> {
    (0..400)
        .map(|k| {
            let t = 0.05 + (std::f64::consts::TAU - 0.1) * k as f64 / 399.0;
            let r = 2.0 + (2.0 * t).cos();
            DVec3::new(r * (3.0 * t).cos(), r * (3.0 * t).sin(), (4.0 * t).sin())
        })
        .collect()
}

#[test]
fn the_writhe_tells_a_trefoil_from_its_mirror_image() {
    let options = KnotOptions::default();
    let right = analyse_knot(&open_torus_trefoil(false), &options).expect("analysed");
    let left = analyse_knot(&open_torus_trefoil(true), &options).expect("analysed");
    assert_eq!((&right.knot, &left.knot), (&KnotType::Trefoil, &KnotType::Trefoil));
    assert_eq!(right.polynomial, left.polynomial);
    let gauss = gauss_writhe(-1.0, 600);
    assert!(gauss > 3.0, "the z = −sin 3t torus trefoil is right-handed: Wr = {gauss}");
    let (w_right, w_left) = (right.writhe.expect("a core"), left.writhe.expect("a core"));
    assert!(w_right > 1.5, "right-handed: writhe {w_right}");
    // Not exactly −w_right: the closure directions are not symmetric under the mirror.
    assert!(w_left < -1.5, "the mirror image is left-handed: writhe {w_left}");
    assert_eq!((right.right_handed(), left.right_handed()), (Some(true), Some(false)));
}

#[test]
fn the_figure_eight_is_achiral() {
    let report = analyse_knot(&open_figure_eight(), &KnotOptions::default()).expect("analysed");
    assert_eq!(report.knot, KnotType::FigureEight);
    let writhe = report.writhe.expect("a core");
    assert!(writhe.abs() < 1.5, "figure-eight writhe {writhe}");
}
