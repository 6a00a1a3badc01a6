//! The rate half of the forward kinematics on random chains: re-evaluated at new rates with
//! the configuration unchanged, it gives exactly what a whole forward kinematics gives.

mod common;

use common::*;
use glam::DVec3;
use hagfish_tree::{forward_kinematics, velocity_kinematics};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn new_rates_give_the_whole_kinematics(
        (spec, q, first, second) in chain_spec(1, 60).prop_flat_map(|spec| {
            let n = build_chain(&spec, DVec3::ZERO, 0.0, 0.0).dof_count();
            (Just(spec), vector(n, 1.5), vector(n, 2.0), vector(n, 2.0))
        })
    ) {
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let mut refreshed = kinematics_at(&model, &q, &first);
        velocity_kinematics(&model, &second, &mut refreshed);
        let mut whole = kinematics_at(&model, &q, &first);
        forward_kinematics(&model, &q, &second, &mut whole);
        prop_assert_eq!(&refreshed.velocities, &whole.velocities);
        prop_assert_eq!(&refreshed.bias_accelerations, &whole.bias_accelerations);
        prop_assert_eq!(&refreshed.axis_rates, &whole.axis_rates);
        prop_assert_eq!(&refreshed.axes, &whole.axes);
    }
}
