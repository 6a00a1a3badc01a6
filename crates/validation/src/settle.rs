//! Running a validation scenario until its phases are over (a load has settled).

use hagfish_anatomy::Rod;
use hagfish_control::{LoadPhase, Phase, PhasedController};
use hagfish_scenario::LoadedScenario;
use hagfish_sim::World;
use hagfish_sim::rows::RowGroup;

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
    /// The self contacts' total normal force N = Σ λ/h over the self-contact rows (each row's
    /// direction d has d·n̂ = 1, so its multiplier λ is its normal impulse), averaged over the
    /// steps of the last second (dyn): a settled knot's contact set can cycle from step to
    /// step (a contact found every other step), and its N with it.
    pub contact_normal_force_dyn: f64,
}

/// The time over whose steps [`Settled::contact_normal_force_dyn`] is averaged (s). On the
/// loose trefoil at 50 dyn the contact set settles into a cycle of two steps (25 and 26
/// contacts) whose N differ by 7 %: the last step's alone is one of the two.
const NORMAL_FORCE_WINDOW_S: f64 = 1.0;

/// The normal forces of `world`'s self contacts over its last step, summed (dyn): the
/// multipliers its last solve gave the self-contact rows, over the time step. A row's
/// direction d has d·n̂ = 1 (the normal alone, or a friction pyramid's edge n̂ + μt̂), so Σ λ/h
/// is the contacts' total normal force N whichever of a pyramid's edges carry it.
fn contact_normal_force_dyn(world: &World) -> f64 {
    let data = world.data();
    let rows = data.rows.sources().iter().zip(data.solver.multipliers());
    let contact = RowGroup::Contact.tag();
    let impulse: f64 = rows.filter(|(row, _)| row.tag == contact).map(|(_, lambda)| lambda).sum();
    impulse / world.options().time_step
}

impl Settled {
    /// World position of the tail end (the far end of the last body, where loads act; cm).
    pub fn tail_end(&self) -> glam::DVec3 {
        let last = self.world.model().body_count() - 1;
        self.body_end(last, 0.5)
    }

    /// The rod's centreline as the polyline of its bodies' ends (cm): the head end of the
    /// first body, then the far end of every body (bodies + 1 points; a body's axis is its
    /// frame's x).
    pub fn body_ends(&self) -> Vec<glam::DVec3> {
        let bodies = self.world.model().body_count();
        let head = (bodies > 0).then(|| self.body_end(0, -0.5));
        head.into_iter().chain((0..bodies).map(|b| self.body_end(b, 0.5))).collect()
    }

    /// The point `side` body lengths along body `b`'s axis from its centre (cm).
    fn body_end(&self, b: usize, side: f64) -> glam::DVec3 {
        let frame = &self.world.data().tree.body_frames[b];
        frame.translation + frame.rotation.col(0) * (side * self.world.model().bodies()[b].length)
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
    let window = (NORMAL_FORCE_WINDOW_S / scenario.time_step_s).round() as usize;
    let mut normal_force = TrailingMean::new(window);
    while !controller.finished() && world.steps() < steps {
        world.step(&mut controller)?;
        normal_force.push(contact_normal_force_dyn(&world));
    }
    if !controller.finished() {
        return Err(ValidationError::NotSettled {
            path: loaded.path.clone(),
            seconds: world.state().t,
            energy_erg: hagfish_tree::kinetic_energy(&world.data().tree),
        });
    }
    let contact_normal_force_dyn = normal_force.mean();
    Ok(Settled { world, controller, rod, load, contact_normal_force_dyn })
}

/// The mean of the last `window` values pushed (a ring of them).
struct TrailingMean {
    values: Vec<f64>,
    window: usize,
    pushed: usize,
}

impl TrailingMean {
    /// A mean over the last `window` values (at least one).
    fn new(window: usize) -> Self {
        let window = window.max(1);
        Self { values: Vec::with_capacity(window), window, pushed: 0 }
    }

    /// Adds `value`, replacing the oldest once `window` are held.
    fn push(&mut self, value: f64) {
        match self.values.len() < self.window {
            true => self.values.push(value),
            false => self.values[self.pushed % self.window] = value,
        }
        self.pushed += 1;
    }

    /// The mean of the values held (NaN before the first).
    fn mean(&self) -> f64 {
        self.values.iter().sum::<f64>() / self.values.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_trailing_mean_holds_the_last_values_only() {
        let mut mean = TrailingMean::new(3);
        assert!(mean.mean().is_nan());
        mean.push(1.0);
        assert_eq!(mean.mean(), 1.0);
        for value in [2.0, 3.0, 10.0, 20.0] {
            mean.push(value);
        }
        assert_eq!(mean.mean(), (3.0 + 10.0 + 20.0) / 3.0);
        mean.push(30.0);
        assert_eq!(mean.mean(), (10.0 + 20.0 + 30.0) / 3.0);
        let mut one = TrailingMean::new(0);
        one.push(4.0);
        one.push(5.0);
        assert_eq!(one.mean(), 5.0);
    }
}
