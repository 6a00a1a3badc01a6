//! A world: one immutable model and options, the minimal state, and the step data.

use hagfish_control::Controller;
use hagfish_tree::{Model, State};

use crate::error::SimError;
use crate::options::StepOptions;
use crate::pipeline;
use crate::report::StepReport;
use crate::retry::{Attempt, ContactResolution};
use crate::step_data::StepData;
use crate::stop::StopRequest;
use crate::warm_start::KeyedMultiplier;

/// A simulated body with everything needed to step it. The model and options never change
/// after construction; [`World::step`] advances the state and refills the data.
#[derive(Debug)]
pub struct World {
    model: Model,
    options: StepOptions,
    state: State,
    data: StepData,
    steps: u64,
    /// The state at the start of the step being taken, to return to if it fails.
    start: State,
}

impl World {
    /// A world at `state`, checked against `model` and `options`.
    pub fn new(model: Model, options: StepOptions, state: State) -> Result<Self, SimError> {
        options.validate()?;
        state.validate(&model).map_err(|source| SimError::Tree {
            step: 0,
            time: state.t,
            source,
        })?;
        let data = StepData::new(&model, &options)?;
        let start = state.clone();
        let mut world = Self { model, options, state, data, steps: 0, start };
        world.prepare()?;
        Ok(world)
    }

    /// The immutable model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The step options.
    pub fn options(&self) -> &StepOptions {
        &self.options
    }

    /// The current state.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The data of the last step (contacts, rows, solver answer, report). Its kinematics are
    /// those of the state at the start of that step (of the initial state before any step).
    pub fn data(&self) -> &StepData {
        &self.data
    }

    /// Whether the next steps compute the joint loads (stage `internal_forces`; default
    /// true). They are only recorded, never used by a step: the run loop asks for them on the
    /// steps that end on a recorded frame, and between those `data().internal` holds the
    /// loads of the last step that computed them.
    pub fn set_internal_forces_due(&mut self, due: bool) {
        self.data.internal_forces_due = due;
    }

    /// Number of steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Replaces the state (checked against the model), e.g. to restart from a saved one.
    pub fn set_state(&mut self, state: State) -> Result<(), SimError> {
        state.validate(&self.model).map_err(|source| SimError::Tree {
            step: self.steps,
            time: state.t,
            source,
        })?;
        self.state = state;
        self.prepare()
    }

    /// The kinematics and contacts of the current state, as the end of a step leaves them
    /// ([`pipeline::check_result`]), so that every step detects contacts once.
    fn prepare(&mut self) -> Result<(), SimError> {
        let (model, options, state) = (&self.model, &self.options, &self.state);
        pipeline::check_result(model, options, state, &mut self.data)
            .map_err(|source| SimError::Geometry { step: self.steps, time: state.t, source })?;
        Ok(())
    }

    /// Continues from a checkpoint: the state, the step counter and the velocity solve's warm
    /// start (the multipliers of the last solve before the checkpoint, by what their rows
    /// constrain: [`crate::WarmStart::carried`]).
    pub fn resume(
        &mut self,
        state: State,
        steps: u64,
        multipliers: &[KeyedMultiplier],
    ) -> Result<(), SimError> {
        self.set_state(state)?;
        self.steps = steps;
        self.data.warm_start.set_carried(multipliers);
        Ok(())
    }

    /// Writes the body centres of the current state into `out` (cm). Recomputes the
    /// kinematics of the current state into the step data.
    pub fn body_centres(&mut self, out: &mut Vec<glam::DVec3>) {
        pipeline::kinematics(&self.model, &self.state, &mut self.data);
        out.clear();
        out.extend((0..self.model.body_count()).map(|i| self.data.tree.body_centre(i)));
    }

    /// The largest excess of a joint angle over its limits in the current state (rad, 0 when
    /// all are within).
    pub fn max_limit_excess(&self) -> f64 {
        pipeline::limit_excess(&self.model, &self.state.q)
    }

    /// Advances one step of `options.time_step` with `controller` deciding the actuation, its
    /// self contacts at the body-relative resolution. A step that fails or whose result is
    /// rejected ([`crate::StepAcceptance`]) leaves the state as it was (the controller is the
    /// caller's to restore); [`World::advance`] retries it.
    pub fn step(&mut self, controller: &mut dyn Controller) -> Result<&StepReport, SimError> {
        let whole = Attempt {
            time_step: self.options.time_step,
            contacts: ContactResolution::BodyRelative,
        };
        self.attempt(controller, whole)?;
        self.steps += 1;
        Ok(&self.data.report)
    }

    /// Advances the state by `attempt.time_step` (the whole step, or a part of it: a rejected
    /// step is retried as substeps) with its self contacts at `attempt.contacts`, without
    /// counting a step; on failure the state is left as it was, as by [`World::step`].
    pub fn attempt(
        &mut self,
        controller: &mut dyn Controller,
        attempt: Attempt,
    ) -> Result<&StepReport, SimError> {
        self.attempt_until(controller, attempt, StopRequest::default())
    }

    /// [`World::attempt`], abandoned with [`SimError::Stopped`] (the state left as it was) at
    /// the first stage boundary after `stop` is set.
    pub(crate) fn attempt_until(
        &mut self,
        controller: &mut dyn Controller,
        attempt: Attempt,
        stop: StopRequest<'_>,
    ) -> Result<&StepReport, SimError> {
        self.set_contact_resolution(attempt.contacts)?;
        // Field by field: the derived `State::clone_from` would allocate new vectors.
        self.start.t = self.state.t;
        self.start.q.clone_from(&self.state.q);
        self.start.qdot.clone_from(&self.state.qdot);
        let result = if attempt.time_step == self.options.time_step {
            let (model, options) = (&self.model, &self.options);
            let at = (self.steps, stop);
            pipeline::step(model, options, &mut self.state, at, &mut self.data, controller)
        } else {
            // A substep corrects a penetration or a head error at the speed the whole step
            // would (β·d/h, not β·d/h_sub): pushed out over h_sub, a 2 % penetration left by the
            // last accepted step came out 16× faster in h/16 substeps, turning a joint past
            // the rate bound at every subdivision (docs/decisions/).
            let scale = attempt.time_step / self.options.time_step;
            let options = StepOptions {
                time_step: attempt.time_step,
                push_out: self.options.push_out * scale,
                head_correction: self.options.head_correction * scale,
                ..self.options.clone()
            };
            let model = &self.model;
            let at = (self.steps, stop);
            pipeline::step(model, &options, &mut self.state, at, &mut self.data, controller)
        };
        if let Err(error) = result {
            std::mem::swap(&mut self.state, &mut self.start);
            self.prepare()?;
            return Err(error);
        }
        Ok(&self.data.report)
    }

    /// Detects self contacts at `resolution` from now on, and the current state's contacts
    /// again if that changes their cluster radius. Returns whether it did: the chain's
    /// resolution changes nothing on chains whose body-relative radius is already that fine
    /// (ES103 and coarser).
    pub fn set_contact_resolution(
        &mut self,
        resolution: ContactResolution,
    ) -> Result<bool, SimError> {
        let radius = match resolution {
            ContactResolution::BodyRelative => {
                self.options.detector_options(&self.model).cluster_radius
            }
            ContactResolution::Chain => self.options.resolved_cluster_radius(&self.model),
        };
        if radius == self.data.detector.options().cluster_radius {
            return Ok(false);
        }
        let (step, time) = (self.steps, self.state.t);
        self.data.detector.set_cluster_radius(radius).map_err(|source| SimError::Geometry {
            step,
            time,
            source,
        })?;
        self.prepare()?;
        Ok(true)
    }

    /// Counts a step taken (whole, or as substeps) by [`World::advance`].
    pub(crate) fn count_step(&mut self) {
        self.steps += 1;
    }
}
