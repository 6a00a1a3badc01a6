//! The hagfish-like case: an overhand knot in a 100-vertex centreline.

use hagfish_knots::{KnotOptions, KnotType, analyse_knot};

use crate::hagfish_curve::{SPACING, VERTICES, hagfish_trefoil};

#[test]
fn overhand_knot_in_a_hagfish_is_a_trefoil_with_its_extent() {
    let (points, tail) = hagfish_trefoil();
    assert_eq!(points.len(), VERTICES);
    let report = analyse_knot(&points, &KnotOptions::default()).expect("valid curve");
    assert_eq!(report.knot, KnotType::Trefoil, "{report:?}");
    assert_eq!(report.polynomial.coefficients(), &[1, -1, 1]);
    assert_eq!(report.determinant, 3);
    assert!(report.agreement >= 0.9, "{report:?}");
    let (first, last) = report.extent.expect("a trefoil has an extent");
    // The knot occupies the vertices between the tails (≈ tail / spacing at each end).
    let knot_first = tail / SPACING;
    let knot_last = (VERTICES - 1) as f64 - tail / SPACING;
    println!("extent {first}..={last}, knot {knot_first:.1}..={knot_last:.1}, {report:?}");
    assert!((first as f64) > knot_first - 6.0 && (first as f64) < knot_first + 10.0, "{report:?}");
    assert!((last as f64) < knot_last + 6.0 && (last as f64) > knot_last - 10.0, "{report:?}");
    let middle = 0.5 * (VERTICES - 1) as f64 * SPACING;
    let position = report.position.expect("with the extent");
    assert!((position - middle).abs() < 3.0, "position {position} vs middle {middle}");
}
