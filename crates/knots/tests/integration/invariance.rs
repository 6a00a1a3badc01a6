//! The knot type does not depend on position, orientation or scale.

use glam::{DQuat, DVec3};
use hagfish_knots::{KnotOptions, KnotType, analyse_knot};
use proptest::prelude::*;

use crate::hagfish_curve::hagfish_trefoil;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn rigid_motions_and_scalings_keep_the_trefoil(
        axis in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
        angle in 0.0..std::f64::consts::TAU,
        shift in (-100.0..100.0f64, -100.0..100.0f64, -100.0..100.0f64),
        log_scale in -5.0..5.0f64,
    ) {
        let axis = DVec3::new(axis.0, axis.1, axis.2).try_normalize().unwrap_or(DVec3::Z);
        let rotation = DQuat::from_axis_angle(axis, angle);
        let (shift, scale) = (DVec3::new(shift.0, shift.1, shift.2), log_scale.exp());
        let moved: Vec<DVec3> =
            hagfish_trefoil().0.iter().map(|&p| scale * (rotation * p) + shift).collect();
        let options = KnotOptions { extent: false, ..KnotOptions::default() };
        let report = analyse_knot(&moved, &options).expect("valid curve");
        prop_assert_eq!(&report.knot, &KnotType::Trefoil);
        prop_assert!(report.agreement >= 0.9, "{:?}", report);
    }
}
