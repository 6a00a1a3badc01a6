//! A request to stop a run, polled between the stages of a step so that a step of a huge body
//! (tens of seconds) does not delay it: set by a signal handler, it ends the step being taken
//! at the next stage boundary, with the state left at the step's start.

use std::sync::atomic::{AtomicBool, Ordering};

use crate::error::{SimError, StepAt};

/// A flag another thread (a signal handler) may set to stop the step being taken; the default
/// never stops.
#[derive(Debug, Clone, Copy, Default)]
pub struct StopRequest<'a>(Option<&'a AtomicBool>);

impl<'a> StopRequest<'a> {
    /// Stops once `flag` is set.
    pub fn new(flag: Option<&'a AtomicBool>) -> Self {
        Self(flag)
    }

    /// The flag, for the solver to poll within a solve
    /// ([`hagfish_solver::Factored::stop_when`]).
    pub fn flag(self) -> Option<&'a AtomicBool> {
        self.0
    }

    /// Whether the stop was asked for.
    pub fn requested(self) -> bool {
        self.0.is_some_and(|flag| flag.load(Ordering::Relaxed))
    }

    /// [`SimError::Stopped`] at `at` if the stop was asked for.
    pub(crate) fn check(self, at: StepAt) -> Result<(), SimError> {
        if self.requested() {
            return Err(SimError::Stopped { step: at.step, time: at.time });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_set_flag_stops() {
        let at = StepAt { step: 7, time: 0.5 };
        assert!(StopRequest::default().check(at).is_ok());
        let flag = AtomicBool::new(false);
        let stop = StopRequest::new(Some(&flag));
        assert!(stop.check(at).is_ok() && !stop.requested());
        flag.store(true, Ordering::Relaxed);
        match stop.check(at) {
            Err(SimError::Stopped { step: 7, time }) => assert_eq!(time, 0.5),
            other => panic!("expected a stop, got {other:?}"),
        }
    }
}
