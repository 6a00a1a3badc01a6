//! The parts of the forward kinematics on random chains: the rate half, re-evaluated at new
//! rates with the configuration unchanged, and the frames alone each give exactly what a whole
//! forward kinematics gives.

use crate::common::*;
use glam::DVec3;
use hagfish_tree::{Data, forward_kinematics, frame_kinematics, velocity_kinematics};
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

    #[test]
    fn the_frames_alone_are_those_of_the_whole_kinematics(
        (spec, q, rates) in chain_spec(1, 60).prop_flat_map(|spec| {
            let n = build_chain(&spec, DVec3::ZERO, 0.0, 0.0).dof_count();
            (Just(spec), vector(n, 1.5), vector(n, 2.0))
        })
    ) {
        let model = build_chain(&spec, DVec3::ZERO, 0.0, 0.0);
        let whole = kinematics_at(&model, &q, &rates);
        let mut frames = Data::new(&model);
        frame_kinematics(&model, &q, &mut frames);
        prop_assert_eq!(&frames.joint_frames, &whole.joint_frames);
        prop_assert_eq!(&frames.body_frames, &whole.body_frames);
        prop_assert_eq!(&frames.axes, &whole.axes);
    }
}
