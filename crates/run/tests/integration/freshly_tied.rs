//! The freshly tied knot several tests step from: `data/scenarios/form.ron` run from rest to
//! t = 17 s, its trefoil just tied; and one thigmotaxis step from it.

use hagfish_control::{
    Actuation, ControlContext, Controller, ForceSpace, SlidingTargets, ThigmoParameters,
};
use hagfish_scenario::LoadedScenario;
use hagfish_sim::World;
use hagfish_sim::rows::RowGroup;
use hagfish_tree::State;

/// Thigmotaxis alone, as a controller.
pub struct Thigmo(pub ThigmoParameters);

impl Controller for Thigmo {
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        self.0.actuate(context, out);
    }
}

/// `form.ron` loaded, its world stepped to 17 s, and that state.
pub fn freshly_tied_knot() -> (LoadedScenario, World, State) {
    let path = format!("{}/../../data/scenarios/form.ron", env!("CARGO_MANIFEST_DIR"));
    let loaded = LoadedScenario::load(&path).expect("form.ron loads");
    let (mut world, mut forming) = loaded.build().expect("world builds");
    while world.state().t < 17.0 {
        world.step(&mut forming).expect("forming step");
    }
    let knotted = world.state().clone();
    (loaded, world, knotted)
}

/// Thigmotaxis with both ends' targets 1 cm/s, no tail pull, a 10⁶ dyn cap and no replay,
/// its rows confined to `force_space`.
pub fn thigmo_parameters(force_space: ForceSpace) -> ThigmoParameters {
    let targets = SlidingTargets { v_a: 1.0, v_b: 1.0 };
    ThigmoParameters {
        head: targets,
        tail: targets,
        tail_pull_dyn: 0.0,
        max_force_dyn: 1e6,
        force_space,
        replay: None,
    }
}

/// One step of thigmotaxis from `knotted` (both ends' targets 1 cm/s, no tail pull, a 10⁶ dyn
/// cap) with its rows confined to `force_space`; returns the step's thigmotaxic generalized
/// force `C_thᵀλ/h` (dyn·cm per DOF). The step's rows stay in `world.data()`.
pub fn thigmo_step(world: &mut World, knotted: &State, force_space: ForceSpace) -> Vec<f64> {
    world.set_state(knotted.clone()).expect("state restores");
    world.step(&mut Thigmo(thigmo_parameters(force_space))).expect("thigmo step");
    let mut force = vec![0.0; world.model().dof_count()];
    world.data().group_force(RowGroup::Thigmo, world.options().time_step, &mut force);
    force
}
