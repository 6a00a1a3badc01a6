//! A scenario's controller: water drag on every step plus a sequence of phases, each with its
//! own way of ending (brief D13: an explicit phase switch, not "first contact").

use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, Controller};
use crate::drag::WaterDrag;
use crate::forming::{FormingController, FormingScript};

/// One phase of a scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Phase {
    /// Scripted knot forming with the tail; ends when the script's last step has ended
    /// (the target is then held by the next phase only if that phase holds it).
    Form(FormingScript),
    /// Keeps the last forming target (if any) for a time (s); the body is otherwise passive.
    Hold(f64),
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
    phases: Vec<Phase>,
    progress: PhaseProgress,
    forming: Option<FormingController>,
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
            None => "done",
        }
    }

    /// True when the current phase is over at time `t`.
    fn phase_over(&self, t: f64) -> bool {
        match self.phases.get(self.progress.phase) {
            Some(Phase::Form(_)) => self.forming.as_ref().is_none_or(FormingController::finished),
            Some(Phase::Hold(seconds)) => t - self.progress.started_at >= *seconds,
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
        while self.progress.phase < self.phases.len() && self.phase_over(context.state.t) {
            self.advance(context.state.t);
        }
        let holds_target =
            matches!(self.phases.get(self.progress.phase), Some(Phase::Form(_) | Phase::Hold(_)));
        if let (true, Some(forming)) = (holds_target, &mut self.forming) {
            forming.control(context, out);
        }
    }
}
