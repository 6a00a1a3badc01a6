//! What a [`PhasedController`] carries from one step to the next, as plain data, so a run can
//! be checkpointed and resumed bit for bit. Water drag and thigmotaxis keep no state of their
//! own; the phases and the forming script do.

use serde::{Deserialize, Serialize};

use crate::error::ControlError;
use crate::forming::{FormingController, ScriptProgress};
use crate::phases::{Phase, PhaseProgress, PhasedController};
use crate::tie::TieProgress;

/// The state of a [`PhasedController`]: which phase, since when, and where the forming script
/// (of the latest `Form` phase so far) is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControllerState {
    /// Phase index and its start time.
    pub phases: PhaseProgress,
    /// Progress of the forming script, if a `Form` (or `Tie`) phase has started.
    pub forming: Option<ScriptProgress>,
    /// Progress of the current `Tie` phase (default otherwise).
    #[serde(default)]
    pub tie: TieProgress,
}

impl PhasedController {
    /// The state to save.
    pub fn state(&self) -> ControllerState {
        ControllerState {
            phases: self.progress,
            forming: self.forming.as_ref().map(|f| *f.progress()),
            tie: self.tie,
        }
    }

    /// Continues from a saved `state` of a controller built from the same phases: the forming
    /// script is the one of the latest `Form` phase up to the current phase.
    pub fn restore(&mut self, state: &ControllerState) -> Result<(), ControlError> {
        let mismatch = ControlError::StateMismatch {
            phase: state.phases.phase,
            phases: self.phases.len(),
            forming: state.forming.is_some(),
        };
        if state.phases.phase > self.phases.len() {
            return Err(mismatch);
        }
        // A tie in progress forms its current attempt's plan (attempts after the first may
        // move at `retry_speed_cm_s`); otherwise the latest script up to the current phase.
        let script = match self.phases.get(state.phases.phase) {
            Some(Phase::Tie(tie)) => Some(tie.script_for(state.tie.attempt.max(1))),
            _ => self.phases[..(state.phases.phase + 1).min(self.phases.len())]
                .iter()
                .rev()
                .find_map(Phase::script),
        };
        self.forming = match (script, state.forming) {
            (Some(script), Some(progress)) if progress.step <= script.steps.len() => {
                Some(FormingController { script, progress })
            }
            (None, None) => None,
            _ => return Err(mismatch),
        };
        self.progress = state.phases;
        self.tie = state.tie;
        self.refresh_tie_checks();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::forming::{FormingScript, ScriptStep};
    use crate::tail_pd::TailGains;

    fn controller(phases: Vec<Phase>) -> PhasedController {
        PhasedController::new(None, phases)
    }

    fn form() -> Phase {
        Phase::Form(FormingScript {
            gains: TailGains::default(),
            steps: vec![ScriptStep::Hold(1.0)],
        })
    }

    #[test]
    fn a_saved_state_comes_back_and_a_foreign_one_is_refused() {
        let phases = vec![form(), Phase::Hold(1.0)];
        let saved = ControllerState {
            phases: PhaseProgress {
                phase: 1,
                started_at: 2.5,
                condition_since: Some(2.7),
                load_since: None,
                pull: None,
                core_start_l: Some(0.3),
                core_length_d: Some(14.0),
                core_length_d_at_start: Some(13.0),
            },
            forming: Some(ScriptProgress {
                step: 1,
                started_at: Some(1.5),
                from: [1.0, 2.0, 3.0],
                to: [1.0, 2.0, 3.0],
                duration: 1.0,
            }),
            tie: TieProgress::default(),
        };
        let mut restored = controller(phases.clone());
        assert_eq!(restored.restore(&saved), Ok(()));
        assert_eq!(restored.state(), saved);
        assert_eq!(restored.phase_name(), "hold");

        let mismatch = |state: &ControllerState| controller(phases.clone()).restore(state).is_err();
        assert!(
            mismatch(&ControllerState { forming: None, ..saved }),
            "Form phase without progress"
        );
        let beyond = PhaseProgress { phase: 3, started_at: 0.0, ..PhaseProgress::default() };
        assert!(mismatch(&ControllerState { phases: beyond, ..saved }), "phase beyond the last");
        let passive = controller(vec![Phase::Hold(1.0)]).restore(&saved);
        assert!(passive.is_err(), "forming progress without a Form phase");
        let finished = ControllerState {
            phases: PhaseProgress { phase: 2, started_at: 3.5, ..PhaseProgress::default() },
            ..saved
        };
        assert!(!mismatch(&finished), "after the last phase the forming script is kept");
    }

    /// A tie in its second attempt comes back with that attempt's plan — moving at
    /// `retry_speed_cm_s` — and its crossing checks, not the first attempt's.
    #[test]
    fn a_tie_in_a_later_attempt_comes_back_with_that_attempts_plan() {
        use crate::tie::{TieKnot, TiePhase};
        let mut tie = TiePhase::new(TieKnot::FigureEight, 0.31);
        tie.speed_cm_s = 3.0;
        tie.retry_speed_cm_s = Some(5.0);
        let phases = vec![Phase::Tie(tie.clone())];
        let mut saved = controller(phases.clone()).state();
        saved.tie = TieProgress { attempt: 2, ..TieProgress::default() };
        let mut restored = controller(phases);
        assert_eq!(restored.restore(&saved), Ok(()));
        let script = &restored.forming.as_ref().expect("a tie forms").script;
        assert_eq!(*script, tie.script_for(2));
        assert_ne!(*script, tie.script_for(1), "the attempts move at different speeds");
        let plan = tie.plan_for(2);
        let checks: Vec<_> = plan.checks().map(|(k, c)| (k, c.clone())).collect();
        assert_eq!(restored.tie_checks, checks);
    }
}
