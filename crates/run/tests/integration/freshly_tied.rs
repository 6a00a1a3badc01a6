//! The freshly tied knot several tests step from: `data/scenarios/form.ron` run from rest to
//! t = 17 s, its trefoil just tied.

use hagfish_scenario::LoadedScenario;
use hagfish_sim::World;
use hagfish_tree::State;

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
