//! A scenario's controller: water drag on every step plus a sequence of phases, each with its
//! own way of ending (brief D13: an explicit phase switch, not "first contact").

use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, Controller};
use crate::drag::WaterDrag;
use crate::forming::{FormingController, FormingScript};
use crate::knot_span::KnotSpan;
use crate::thigmotaxis::ThigmoParameters;

/// One phase of a scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Phase {
    /// Scripted knot forming with the tail; ends when the script's last step has ended
    /// (the target is then held by the next phase only if that phase holds it).
    Form(FormingScript),
    /// Keeps the last forming target (if any) for a time (s); the body is otherwise passive.
    Hold(f64),
    /// Thigmotaxic inverse dynamics on the first and last self contact until a condition.
    Thigmotaxis(ThigmoPhase),
}

/// A thigmotaxis phase: its parameters and when it ends.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThigmoPhase {
    /// Targets, tail pull and force cap.
    pub parameters: ThigmoParameters,
    /// When the phase ends.
    pub until: Until,
}

/// End conditions of a phase; it ends at the first that holds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Until {
    /// Longest duration (s).
    pub seconds: f64,
    /// Ends once the knot's anterior end is this close to the head (cm of arc length).
    #[serde(default)]
    pub knot_start_below_cm: Option<f64>,
    /// Ends once the knot's anterior end is this far from the head (cm; sliding tail-ward).
    #[serde(default)]
    pub knot_start_above_cm: Option<f64>,
}

/// Progress through the phases: the controller state a checkpoint must keep.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PhaseProgress {
    /// Index of the current phase (`phases.len()` after the last: passive).
    pub phase: usize,
    /// Time the current phase started (s).
    pub started_at: f64,
}

/// Drag plus phases, in order.
#[derive(Clone, Debug)]
pub struct PhasedController {
    drag: Option<WaterDrag>,
    pub(crate) phases: Vec<Phase>,
    pub(crate) progress: PhaseProgress,
    pub(crate) forming: Option<FormingController>,
}

impl PhasedController {
    /// A controller at the start of the first phase.
    pub fn new(drag: Option<WaterDrag>, phases: Vec<Phase>) -> Self {
        let forming = match phases.first() {
            Some(Phase::Form(script)) => Some(FormingController::new(script.clone())),
            _ => None,
        };
        Self { drag, phases, progress: PhaseProgress::default(), forming }
    }

    /// Where the controller is.
    pub fn progress(&self) -> &PhaseProgress {
        &self.progress
    }

    /// A short name of the current phase for tables: "form", "hold" or "done".
    pub fn phase_name(&self) -> &'static str {
        match self.phases.get(self.progress.phase) {
            Some(Phase::Form(_)) => "form",
            Some(Phase::Hold(_)) => "hold",
            Some(Phase::Thigmotaxis(_)) => "thigmo",
            None => "done",
        }
    }

    /// True when the current phase is over.
    fn phase_over(&self, context: &ControlContext<'_>) -> bool {
        let elapsed = context.state.t - self.progress.started_at;
        match self.phases.get(self.progress.phase) {
            Some(Phase::Form(_)) => self.forming.as_ref().is_none_or(FormingController::finished),
            Some(Phase::Hold(seconds)) => elapsed >= *seconds,
            Some(Phase::Thigmotaxis(phase)) => {
                let start =
                    KnotSpan::of(context.self_contacts, context.centreline).map(|s| s.start_cm);
                let reached = |limit: Option<f64>, beyond: &dyn Fn(f64, f64) -> bool| matches!((limit, start), (Some(l), Some(s)) if beyond(s, l));
                elapsed >= phase.until.seconds
                    || reached(phase.until.knot_start_below_cm, &|s, l| s <= l)
                    || reached(phase.until.knot_start_above_cm, &|s, l| s >= l)
            }
            None => false,
        }
    }

    fn advance(&mut self, t: f64) {
        self.progress = PhaseProgress { phase: self.progress.phase + 1, started_at: t };
        if let Some(Phase::Form(script)) = self.phases.get(self.progress.phase) {
            self.forming = Some(FormingController::new(script.clone()));
        }
    }
}

impl Controller for PhasedController {
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        if let Some(drag) = &mut self.drag {
            drag.control(context, out);
        }
        while self.progress.phase < self.phases.len() && self.phase_over(context) {
            self.advance(context.state.t);
        }
        match self.phases.get(self.progress.phase) {
            Some(Phase::Form(_) | Phase::Hold(_)) => {
                if let Some(forming) = &mut self.forming {
                    forming.control(context, out);
                }
            }
            Some(Phase::Thigmotaxis(phase)) => phase.parameters.actuate(context, out),
            None => {}
        }
    }
}
