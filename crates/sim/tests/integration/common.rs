//! Test controllers shared by the integration tests of `hagfish-sim`.

use glam::DVec3;
use hagfish_control::{Actuation, ControlContext, Controller, PointForce};

/// A force (dyn) on the tail body's centre that sweeps around the body axis and pulls toward
/// the wall, so the tail is dragged around, bends joints into their limits and meets the wall.
pub struct SweepingTailForce(pub f64);

impl Controller for SweepingTailForce {
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        let tail = context.model.body_count() - 1;
        let phase = 1.5 * context.state.t;
        let direction = DVec3::new(-1.0, phase.cos(), phase.sin()).normalize();
        out.forces.push(PointForce {
            body: tail,
            point: context.centre(tail),
            force: direction * self.0,
        });
    }
}
