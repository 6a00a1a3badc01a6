//! Open-loop replay (`ThigmoParameters::replay`): the phase exerts no row force, and its field
//! enters the step as joint torques τ_ext, so the velocity change it makes from rest is
//! linear in a small field (to 10⁻⁶) and does positive work.

use std::sync::Arc;

use hagfish_control::{
    Actuation, ControlContext, Controller, ForceSpace, Replay, ReplayField, ThigmoParameters,
};
use hagfish_scenario::LoadedScenario;
use hagfish_sim::rows::RowGroup;

use crate::freshly_tied::thigmo_parameters;

/// A thigmotaxis phase `since` seconds after it began, as a controller.
struct ThigmoSince(ThigmoParameters, f64);

impl Controller for ThigmoSince {
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        self.0.actuate_since(self.1, context, out);
    }
}

#[test]
fn a_replay_applies_its_field_as_joint_torques_and_no_row_force() {
    let path = format!("{}/../../data/scenarios/form.ron", env!("CARGO_MANIFEST_DIR"));
    let loaded = LoadedScenario::load(&path).expect("form.ron loads");
    let (mut world, _) = loaded.build().expect("world builds");
    let rest = world.state().clone();
    let n = world.model().dof_count();
    // A field constant in time: pattern(d) = sin(d) dyn·cm, scaled; sampled at τ = 0.5 s.
    let pattern: Vec<f64> = (0..n).map(|d| (d as f64).sin()).collect();
    let mut step = |scale: f64| {
        let values = [&pattern[..], &pattern[..]].concat().iter().map(|v| scale * v).collect();
        let field = ReplayField::new(vec![0.0, 1.0], n, values).expect("a field");
        let parameters = ThigmoParameters {
            replay: Some(Replay { file: "test".into(), field: Some(Arc::new(field)) }),
            ..thigmo_parameters(ForceSpace::Full)
        };
        world.set_state(rest.clone()).expect("state restores");
        world.step(&mut ThigmoSince(parameters, 0.5)).expect("a step");
        let mut force = vec![0.0; n];
        world.data().group_force(RowGroup::Thigmo, world.options().time_step, &mut force);
        assert!(force.iter().all(|f| *f == 0.0), "a replay asks no thigmotaxis row");
        world.state().qdot.clone()
    };
    // Small torques, so that what is not linear in them in a step (water drag at the new
    // velocity) stays far below the linear part.
    let (still, once, twice) = (step(0.0), step(1e-3), step(2e-3));
    let delta1: Vec<f64> = once.iter().zip(&still).map(|(a, b)| a - b).collect();
    let delta2: Vec<f64> = twice.iter().zip(&still).map(|(a, b)| a - b).collect();
    let norm = delta1.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(norm > 1e-9, "the torques move the body: |Δq̇| = {norm}");
    let work: f64 = delta1.iter().zip(&pattern).map(|(d, t)| d * t).sum();
    assert!(work > 0.0, "τᵀΔq̇ = h τᵀM̃⁻¹τ > 0, got {work}");
    for (d1, d2) in delta1.iter().zip(&delta2) {
        assert!((d2 - 2.0 * d1).abs() <= 1e-6 * norm, "linear in the field: {d1} {d2}");
    }
}
