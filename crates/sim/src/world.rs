//! A world: one immutable model and options, the minimal state, and the step data.

use hagfish_control::Controller;
use hagfish_tree::{Model, State};

use crate::error::SimError;
use crate::options::StepOptions;
use crate::pipeline;
use crate::report::StepReport;
use crate::step_data::StepData;

/// A simulated body with everything needed to step it. The model and options never change
/// after construction; [`World::step`] advances the state and refills the data.
#[derive(Debug)]
pub struct World {
    model: Model,
    options: StepOptions,
    state: State,
    data: StepData,
    steps: u64,
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
        let mut data = StepData::new(&model, &options)?;
        pipeline::kinematics(&model, &state, &mut data);
        Ok(Self { model, options, state, data, steps: 0 })
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
        pipeline::kinematics(&self.model, &self.state, &mut self.data);
        Ok(())
    }

    /// Continues from a checkpoint: the state, the step counter and the velocity solve's warm
    /// start (the multipliers of the last solve before the checkpoint).
    pub fn resume(
        &mut self,
        state: State,
        steps: u64,
        multipliers: &[f64],
    ) -> Result<(), SimError> {
        self.set_state(state)?;
        self.steps = steps;
        self.data.solver.set_multipliers(multipliers);
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
        let dofs = self.model.dofs().iter().zip(&self.state.q);
        dofs.map(|(d, q)| (d.lower - q).max(q - d.upper)).fold(0.0, f64::max)
    }

    /// Advances one step of `options.time_step` with `controller` deciding the actuation.
    pub fn step(&mut self, controller: &mut dyn Controller) -> Result<&StepReport, SimError> {
        let (model, options) = (&self.model, &self.options);
        pipeline::step(model, options, &mut self.state, self.steps, &mut self.data, controller)?;
        self.steps += 1;
        Ok(&self.data.report)
    }
}
