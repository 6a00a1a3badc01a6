//! Running a validation scenario until its phases are over (a load has settled).

use hagfish_anatomy::Rod;
use hagfish_control::{LoadPhase, Phase, PhasedController};
use hagfish_scenario::LoadedScenario;
use hagfish_sim::World;

use crate::error::ValidationError;

/// A scenario run until its phases ended: the world and the rod and load it was run with.
pub struct Settled {
    /// The world at the end.
    pub world: World,
    /// The controller at the end.
    pub controller: PhasedController,
    /// The rod.
    pub rod: Rod,
    /// The scenario's last load phase: the load the rod settled under (a scenario that
    /// loads it twice, as a frictional knot opened onto a smaller pull, ends with it).
    pub load: LoadPhase,
}

impl Settled {
    /// World position of the tail end (the far end of the last body, where loads act; cm).
    pub fn tail_end(&self) -> glam::DVec3 {
        let data = &self.world.data().tree;
        let last = self.world.model().body_count() - 1;
        let frame = &data.body_frames[last];
        frame.translation + frame.rotation.col(0) * (0.5 * self.world.model().bodies()[last].length)
    }
}

/// The rod and last load phase of `loaded`, or why the scenario is not a rod under a load.
pub fn rod_and_load(loaded: &LoadedScenario) -> Result<(Rod, LoadPhase), ValidationError> {
    let not = |reason: &str| ValidationError::Scenario {
        path: loaded.path.clone(),
        reason: reason.to_string(),
    };
    let hagfish_anatomy::Body::Rod(rod) = &loaded.body else {
        return Err(not("its body is not a rod"));
    };
    let load = loaded.scenario.phases.iter().rev().find_map(|p| match p {
        Phase::Load(load) => Some(load.clone()),
        _ => None,
    });
    Ok((rod.clone(), load.ok_or_else(|| not("it has no load phase"))?))
}

/// Runs `loaded` from rest until its phases are over (it must end in a settling phase): the
/// step of the simulator, one call per step, no recording.
pub fn settle(loaded: &LoadedScenario) -> Result<Settled, ValidationError> {
    let (rod, load) = rod_and_load(loaded)?;
    let (mut world, mut controller) = loaded.build()?;
    let scenario = &loaded.scenario;
    let steps = (scenario.duration_s / scenario.time_step_s).round() as u64;
    while !controller.finished() && world.steps() < steps {
        world.step(&mut controller)?;
    }
    if !controller.finished() {
        return Err(ValidationError::NotSettled {
            path: loaded.path.clone(),
            seconds: world.state().t,
            energy_erg: hagfish_tree::kinetic_energy(&world.data().tree),
        });
    }
    Ok(Settled { world, controller, rod, load })
}
