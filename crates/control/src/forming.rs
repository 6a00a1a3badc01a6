//! The scripted knot-forming controller (thesis §3.3.1 and §5.1; D13).
//!
//! A PD pull on the last body ([`TailGains`]) follows a target that moves at a constant speed
//! through a script of waypoints: crossover → tail wrap → tail insertion → tighten. A limp
//! chain moves while the tail travels, so fixed world waypoints miss the loop (the peer
//! engine's experience): each waypoint is *resolved from the body's current shape* at the
//! moment the target starts moving toward it ("2.5 cm above body 22", "below the centroid of
//! the loop").

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, Controller};
use crate::loops::largest_projected_loop;
use crate::tail_pd::TailGains;

/// Where a waypoint is, resolved when the move toward it starts.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Waypoint {
    /// A fixed world point (cm).
    Point([f64; 3]),
    /// An offset (cm) from the centre of a body.
    FromBody {
        /// Body index (0 = head).
        body: usize,
        /// Offset (cm).
        offset: [f64; 3],
    },
    /// An offset (cm) from the current target (the end of the previous move).
    FromTarget([f64; 3]),
    /// An offset (cm) from the centroid of the largest loop of the centreline seen from
    /// above (+Z); from the centroid of the posterior half of the body if there is no loop.
    FromLoopCentroid([f64; 3]),
    /// A world point in body lengths: (x, y, z)·L, with L the sum of the segment lengths
    /// (the head is at the origin and the body at rest lies along +X).
    BodyLengths([f64; 3]),
    /// An offset in local radii from the centre of the body at arc-length fraction `at` of L
    /// from the head: `c(k) + r_k·offset`, k = the body containing arc length `at·L`.
    FromArc {
        /// Fraction of the body length from the head, in [0, 1].
        at: f64,
        /// Offset (x, y, z) in units of that body's radius.
        offset_radii: [f64; 3],
    },
    /// [`Waypoint::FromLoopCentroid`] with the offset in mean body radii.
    FromLoopCentroidRadii([f64; 3]),
    /// [`Waypoint::FromTarget`] with the offset in mean body radii.
    FromTargetRadii([f64; 3]),
}

/// One step of a script.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum ScriptStep {
    /// Move the target in a straight line to a waypoint at a constant speed (cm/s).
    Move {
        /// Where to.
        to: Waypoint,
        /// Speed of the target (cm/s), > 0.
        speed: f64,
    },
    /// Keep the target still for a time (s).
    Hold(f64),
}

/// A knot-forming script: tail gains and the steps.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FormingScript {
    /// Gains of the tail pull.
    pub gains: TailGains,
    /// The steps, in order; after the last, the target is held where it is.
    pub steps: Vec<ScriptStep>,
}

/// Progress through the script: the controller state that a checkpoint must keep.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ScriptProgress {
    /// Index of the current step (`steps.len()` when finished).
    pub step: usize,
    /// Time the current step started (s); `None` before it is resolved.
    pub started_at: Option<f64>,
    /// Target at the start of the current step (cm).
    pub from: [f64; 3],
    /// Target at the end of the current step (cm).
    pub to: [f64; 3],
    /// Duration of the current step (s).
    pub duration: f64,
}

/// Follows a [`FormingScript`] with the tail.
#[derive(Clone, Debug, PartialEq)]
pub struct FormingController {
    pub(crate) script: FormingScript,
    pub(crate) progress: ScriptProgress,
}

impl FormingController {
    /// A controller at the start of `script`; its first move starts from the tail's position.
    pub fn new(script: FormingScript) -> Self {
        Self { script, progress: ScriptProgress::default() }
    }

    /// The progress through the script.
    pub fn progress(&self) -> &ScriptProgress {
        &self.progress
    }

    /// True once every step has ended (the target is then held).
    pub fn finished(&self) -> bool {
        self.progress.step >= self.script.steps.len()
    }

    /// Starts the current step at time `t` from `from`, resolving its waypoint now.
    fn start_step(&mut self, context: &ControlContext<'_>, from: DVec3) {
        let (to, duration) = match self.script.steps.get(self.progress.step) {
            Some(ScriptStep::Move { to, speed }) => {
                let to = resolve(to, context, from);
                (to, (to - from).length() / speed.max(f64::MIN_POSITIVE))
            }
            Some(ScriptStep::Hold(seconds)) => (from, *seconds),
            None => (from, f64::INFINITY),
        };
        self.progress.started_at = Some(context.state.t);
        self.progress.from = from.to_array();
        self.progress.to = to.to_array();
        self.progress.duration = duration;
    }

    /// The target and its velocity at time `t`, advancing through finished steps.
    fn target(&mut self, context: &ControlContext<'_>) -> (DVec3, DVec3) {
        let t = context.state.t;
        loop {
            let Some(start) = self.progress.started_at else {
                let tail = context.centre(context.model.body_count() - 1);
                self.start_step(context, tail);
                continue;
            };
            let (from, to) =
                (DVec3::from_array(self.progress.from), DVec3::from_array(self.progress.to));
            let elapsed = t - start;
            if elapsed < self.progress.duration || self.finished() {
                let fraction = if self.progress.duration > 0.0 {
                    (elapsed / self.progress.duration).min(1.0)
                } else {
                    1.0
                };
                let velocity = if self.finished() {
                    DVec3::ZERO
                } else {
                    (to - from) / self.progress.duration
                };
                return (from + (to - from) * fraction, velocity);
            }
            self.progress.step += 1;
            self.start_step(context, to);
        }
    }
}

impl Controller for FormingController {
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        let (target, velocity) = self.target(context);
        self.script.gains.pull(context, target, velocity, out);
    }
}

fn resolve(waypoint: &Waypoint, context: &ControlContext<'_>, current: DVec3) -> DVec3 {
    let body_count = context.model.body_count();
    match *waypoint {
        Waypoint::Point(p) => DVec3::from_array(p),
        Waypoint::FromBody { body, offset } => {
            context.centre(body.min(body_count - 1)) + DVec3::from_array(offset)
        }
        Waypoint::FromTarget(offset) => current + DVec3::from_array(offset),
        Waypoint::FromLoopCentroid(offset) => loop_centroid(context) + DVec3::from_array(offset),
        Waypoint::BodyLengths(point) => body_length(context) * DVec3::from_array(point),
        Waypoint::FromArc { at, offset_radii } => {
            let body = body_at_fraction(context, at);
            let radius = context.model.bodies()[body].radius;
            context.centre(body) + radius * DVec3::from_array(offset_radii)
        }
        Waypoint::FromLoopCentroidRadii(offset) => {
            loop_centroid(context) + mean_radius(context) * DVec3::from_array(offset)
        }
        Waypoint::FromTargetRadii(offset) => {
            current + mean_radius(context) * DVec3::from_array(offset)
        }
    }
}

/// The centroid of the largest loop seen from above, or of the posterior half of the body.
fn loop_centroid(context: &ControlContext<'_>) -> DVec3 {
    let body_count = context.model.body_count();
    let centres: Vec<DVec3> = (0..body_count).map(|i| context.centre(i)).collect();
    largest_projected_loop(&centres, DVec3::Z).map_or_else(
        || centres[body_count / 2..].iter().sum::<DVec3>() / (body_count - body_count / 2) as f64,
        |l| l.centroid,
    )
}

/// The body length L: the sum of the segment lengths (cm).
pub(crate) fn body_length(context: &ControlContext<'_>) -> f64 {
    context.model.bodies().iter().map(|b| b.length).sum()
}

/// The mean body radius (cm).
fn mean_radius(context: &ControlContext<'_>) -> f64 {
    let bodies = context.model.bodies();
    bodies.iter().map(|b| b.radius).sum::<f64>() / bodies.len() as f64
}

/// The body containing arc length `at·L` from the head (the last body for `at` ≥ 1).
pub(crate) fn body_at_fraction(context: &ControlContext<'_>, at: f64) -> usize {
    let target = at * body_length(context);
    let mut walked = 0.0;
    for (k, body) in context.model.bodies().iter().enumerate() {
        walked += body.length;
        if walked > target {
            return k;
        }
    }
    context.model.body_count() - 1
}
