//! Taking a step of h whatever it takes: the one place where a rejected step
//! ([`crate::StepAcceptance`]) is retried.
//!
//! ```text
//! whole step ─ accepted ─────────────────────────────────────────────→ Accepted
//!    │ rejected or failed
//!    ├→ whole again, self contacts at the chain's resolution ─ accepted → ResolvedContacts
//!    │     (acceptance.resolve_contacts, on chains where that is finer)
//!    │ rejected or failed
//!    └→ 2, 4, … 2^k substeps of h/2^j, each accepted, from the same start ─→ Substeps(2^j)
//!          (k = acceptance.max_halvings; still at the chain's resolution) ─ none → Failed
//! ```
//!
//! Each attempt starts from the step's start: the state (restored by the world) and the
//! controller (restored from its [`RetryableController::snapshot`]). Each attempt's length and
//! contact resolution are passed in as an [`Attempt`]; the world's options never change. What
//! the taken step adds to a record — its forces, maxima and timings — goes into a
//! [`StepTally`] once the step is taken: an attempt that fails adds nothing but its timings.
//! The tally also holds the scratch of the substeps, so retries allocate only once.

use hagfish_control::{ControlError, Controller, ControllerState, PhasedController};

use crate::error::SimError;
use crate::forces::GroupForces;
use crate::maxima::IntervalMaxima;
use crate::report::{StageTimings, StepReport};
use crate::stop::StopRequest;
use crate::world::World;

/// How a step of h was taken, or why it could not be.
#[derive(Debug)]
pub enum StepOutcome {
    /// Accepted whole, as first solved.
    Accepted,
    /// Rejected whole, then accepted whole with its self contacts at the chain's resolution
    /// ([`crate::StepOptions::resolved_cluster_radius`]).
    ResolvedContacts,
    /// Rejected whole, then taken as `divisions` substeps of h/`divisions`, each accepted.
    Substeps {
        /// How many substeps (a power of two).
        divisions: u32,
    },
    /// Not taken: every attempt failed or was rejected. The state is the step's start; the
    /// error is the whole step's, with the last division's when substeps were tried
    /// ([`SimError::StepFailedWithSubsteps`]).
    Failed(SimError),
    /// Not taken: the stop asked for by [`World::advance`]'s [`StopRequest`] ended it at a
    /// stage boundary (of the whole step or of a retry). The state and the controller are
    /// the step's start.
    Stopped,
}

/// One attempt at (part of) a step: its length and the resolution of its self contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attempt {
    /// Its length (s): the world's time step, or a part of it for a substep.
    pub time_step: f64,
    /// The cluster radius its self contacts are detected at.
    pub contacts: ContactResolution,
}

/// The cluster radius of self-contact detection during an attempt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactResolution {
    /// Body-relative ([`crate::StepOptions::detector_options`]): every first attempt.
    BodyRelative,
    /// The chain's resolution ([`crate::StepOptions::resolved_cluster_radius`]): the
    /// retries of a rejected step, where `acceptance.resolve_contacts` asks for them.
    Chain,
}

/// A controller that can be returned to the state it had at the start of a step, so that a
/// rejected step is taken again from the same start.
pub trait RetryableController: Controller {
    /// What is saved: everything that decides the controller's next actions.
    type Snapshot;
    /// The controller's state now.
    fn snapshot(&self) -> Self::Snapshot;
    /// Returns to a saved state.
    fn restore(&mut self, snapshot: &Self::Snapshot) -> Result<(), ControlError>;
}

impl RetryableController for PhasedController {
    type Snapshot = ControllerState;

    fn snapshot(&self) -> ControllerState {
        self.state()
    }

    fn restore(&mut self, snapshot: &ControllerState) -> Result<(), ControlError> {
        PhasedController::restore(self, snapshot)
    }
}

/// What the steps taken since it was last cleared add up to: the constraint impulses per
/// group, the worst penetrations and limit excess, the report of the last (sub)step, and the
/// wall-clock time per stage (of every accepted attempt, substeps of failed divisions too).
#[derive(Debug, Clone, Default)]
pub struct StepTally {
    /// Impulses per recorded group, summed over the steps taken.
    pub forces: GroupForces,
    /// Worst values over the steps taken.
    pub maxima: IntervalMaxima,
    /// The report of the last accepted (sub)step.
    pub last_report: StepReport,
    /// Seconds per stage.
    pub timings: StageTimings,
    /// The impulses of the substeps of the division being tried (scratch).
    division_forces: GroupForces,
    /// The maxima of the substeps of the division being tried (scratch).
    division_maxima: IntervalMaxima,
}

impl World {
    /// Takes one step of h, retrying it as the module docs draw, and adds it to `tally` once
    /// taken. Every attempt after the first starts from the step's start (state and
    /// `controller`); a failed step leaves both there, and so does a step that `stop` ends
    /// (polled between the stages of every attempt: [`StepOutcome::Stopped`]).
    pub fn advance<C: RetryableController>(
        &mut self,
        controller: &mut C,
        tally: &mut StepTally,
        stop: StopRequest<'_>,
    ) -> StepOutcome {
        let saved = controller.snapshot();
        let first = match self.whole_step(controller, ContactResolution::BodyRelative, tally, stop)
        {
            Ok(()) => return StepOutcome::Accepted,
            Err(error) => error,
        };
        let outcome = match first {
            SimError::Stopped { .. } => StepOutcome::Stopped,
            first => self.retry(controller, &saved, first, (tally, stop)),
        };
        let outcome = match outcome {
            // The controller ran in the abandoned attempt: back to the step's start.
            StepOutcome::Stopped => match controller.restore(&saved) {
                Ok(()) => StepOutcome::Stopped,
                Err(error) => StepOutcome::Failed(error.into()),
            },
            outcome => outcome,
        };
        match self.set_contact_resolution(ContactResolution::BodyRelative) {
            Ok(_) => outcome,
            Err(error) => StepOutcome::Failed(error),
        }
    }

    /// The retries of a step whose whole attempt failed with `first`: whole at the chain's
    /// resolution where that is finer and asked for, then substeps.
    fn retry<C: RetryableController>(
        &mut self,
        controller: &mut C,
        saved: &C::Snapshot,
        first: SimError,
        (tally, stop): (&mut StepTally, StopRequest<'_>),
    ) -> StepOutcome {
        let resolved = if self.options().acceptance.resolve_contacts {
            match self.set_contact_resolution(ContactResolution::Chain) {
                Ok(changed) => changed,
                Err(error) => return StepOutcome::Failed(error),
            }
        } else {
            false
        };
        let contacts =
            if resolved { ContactResolution::Chain } else { ContactResolution::BodyRelative };
        if resolved {
            if let Err(error) = controller.restore(saved) {
                return StepOutcome::Failed(error.into());
            }
            match self.whole_step(controller, contacts, tally, stop) {
                Ok(()) => return StepOutcome::ResolvedContacts,
                Err(SimError::Stopped { .. }) => return StepOutcome::Stopped,
                Err(_) => {}
            }
        }
        match self.subdivide(controller, saved, (contacts, first), tally, stop) {
            Ok(divisions) => StepOutcome::Substeps { divisions },
            Err(SimError::Stopped { .. }) => StepOutcome::Stopped,
            Err(error) => StepOutcome::Failed(error),
        }
    }

    /// One whole attempt of h; its forces and maxima are added to `tally` if it is accepted.
    fn whole_step<C: RetryableController>(
        &mut self,
        controller: &mut C,
        contacts: ContactResolution,
        tally: &mut StepTally,
        stop: StopRequest<'_>,
    ) -> Result<(), SimError> {
        let attempt = Attempt { time_step: self.options().time_step, contacts };
        let report = *self.attempt_until(controller, attempt, stop)?;
        self.count_step();
        tally.last_report = report;
        tally.forces.add_step(self.data(), self.model().dof_count());
        tally.maxima.include(&report, self.max_limit_excess());
        tally.timings.accumulate(&report.timings);
        Ok(())
    }

    /// The step as 2, 4, … 2^k substeps (k = `acceptance.max_halvings`) from the same start
    /// (state, and controller `saved`), the first division whose substeps are all accepted;
    /// `first` is the whole step's error, reported if none is. Returns the divisions; a stop
    /// (`stop`) ends it with [`SimError::Stopped`] and the state at the step's start.
    fn subdivide<C: RetryableController>(
        &mut self,
        controller: &mut C,
        saved: &C::Snapshot,
        (contacts, first): (ContactResolution, SimError),
        tally: &mut StepTally,
        stop: StopRequest<'_>,
    ) -> Result<u32, SimError> {
        let dofs = self.model().dof_count();
        let h = self.options().time_step;
        let start = self.state().clone();
        let mut last = None;
        for halvings in 1..=self.options().acceptance.max_halvings {
            let divisions = 1u32 << halvings;
            controller.restore(saved)?;
            tally.division_forces.clear();
            tally.division_maxima = IntervalMaxima::default();
            let attempt = Attempt { time_step: h / f64::from(divisions), contacts };
            match self.substeps(controller, attempt, divisions, (tally, stop)) {
                Ok(()) => {
                    self.count_step();
                    tally.division_forces.count_as_one_step();
                    tally.forces.absorb(&tally.division_forces, dofs);
                    tally.maxima.merge(&tally.division_maxima);
                    return Ok(divisions);
                }
                Err(error) => {
                    self.set_state(start.clone())?;
                    if let SimError::Stopped { .. } = error {
                        return Err(error);
                    }
                    last = Some((divisions, error));
                }
            }
        }
        controller.restore(saved)?;
        Err(match last {
            None => first,
            Some((divisions, last)) => SimError::StepFailedWithSubsteps {
                first: Box::new(first),
                divisions,
                substep_s: h / f64::from(divisions),
                last: Box::new(last),
            },
        })
    }

    /// `divisions` substeps of `attempt`, each accepted, adding their forces and maxima to
    /// the division's and their timings to `tally`.
    fn substeps<C: RetryableController>(
        &mut self,
        controller: &mut C,
        attempt: Attempt,
        divisions: u32,
        (tally, stop): (&mut StepTally, StopRequest<'_>),
    ) -> Result<(), SimError> {
        let dofs = self.model().dof_count();
        for _ in 0..divisions {
            let report = *self.attempt_until(controller, attempt, stop)?;
            tally.last_report = report;
            tally.division_forces.add_impulses(self.data(), dofs);
            tally.division_maxima.include(&report, self.max_limit_excess());
            tally.timings.accumulate(&report.timings);
        }
        Ok(())
    }
}
