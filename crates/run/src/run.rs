//! Running a scenario: step the world, record frames, check the knot, report progress, and
//! hand a checkpoint to the sink after every frame. A run starts at rest or from a
//! [`Checkpoint`], and ends completed, interrupted (asked to stop after a frame) or diverged
//! (a step failed: the state is kept as it was before that step).

use std::sync::atomic::{AtomicBool, Ordering};

use glam::DVec3;
use hagfish_control::{KnotObservation, KnotSpan, PhasedController};
use hagfish_knots::{KnotAnalyser, KnotOptions, KnotReport};
use hagfish_scenario::{LoadedScenario, Scenario};
use hagfish_sim::rows::RowGroup;
use hagfish_sim::{
    DofLabel, IntervalMaxima, SimError, StageTimings, StepOutcome, StepTally, StopRequest, World,
    dof_arc_lengths, dof_labels,
};
use hagfish_tree::State;

use crate::checkpoint::{
    CHECKPOINT_FILE, CHECKPOINT_FORMAT, CarriedMultipliers, Checkpoint, ExactF64s,
};
use crate::error::RunError;
use crate::force_field::ForceFieldLog;
use crate::knot_core::KnotCore;
use crate::recorder::{Frame, FrameSink};

/// Progress of a run, given to the caller after every recorded frame.
#[derive(Clone, Copy, Debug)]
pub struct Progress<'a> {
    /// Simulated time (s).
    pub time: f64,
    /// Total simulated time of the run (s); at most that when `ends_with_phases`.
    pub duration: f64,
    /// Whether the run ends once its phases have (`end_after_phases`), `duration` being only
    /// a cap.
    pub ends_with_phases: bool,
    /// Frames recorded so far (in the whole run, before a resume included).
    pub frames: usize,
    /// Steps taken so far (in the whole run).
    pub steps: u64,
    /// The latest knot analysis, if any.
    pub knot: Option<&'a KnotReport>,
    /// Current phase.
    pub phase: &'a str,
}

/// One recorded frame's knot analysis, kept for the summary.
#[derive(Clone, Debug)]
pub struct KnotSample {
    /// Simulation time (s).
    pub time: f64,
    /// The analysis (or `None` if it failed for this frame).
    pub knot: Option<KnotReport>,
}

/// What a run reports.
#[derive(Clone, Debug, Default)]
pub struct RunSummary {
    /// Steps taken (in the whole run, before a resume included).
    pub steps: u64,
    /// Frames recorded (in the whole run).
    pub frames: usize,
    /// Knot analysis of every frame recorded by this call.
    pub knots: Vec<KnotSample>,
    /// Worst penetrations and limit excess over the whole run.
    pub maxima: IntervalMaxima,
    /// Wall-clock seconds per stage, summed over the steps of this call.
    pub timings: StageTimings,
    /// The thigmotaxic force field of every frame recorded by this call.
    pub force_field: ForceFieldLog,
    /// Steps whose whole-step result was rejected and that were taken as substeps (in the
    /// whole run).
    pub substepped_steps: u64,
    /// The most substeps one step needed (1 when none was divided).
    pub max_substeps: u32,
    /// Steps whose whole-step result was rejected and that were taken again whole, accepted,
    /// with self contacts at the chain's resolution (`acceptance.resolve_contacts`; in the
    /// whole run).
    pub resolved_steps: u64,
    /// The cluster radius (bodies) of those retries ([`crate::StepOptions::
    /// resolved_cluster_radius`]).
    pub resolved_cluster_bodies: f64,
    /// The phase still running when the run stopped, if any
    /// ([`hagfish_control::PhasedController::unfinished_phase`]): a run whose duration ends
    /// during its tie says that its knot was never tied.
    pub unfinished_phase: Option<String>,
}

/// Where a run starts and when it stops early.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOptions<'a> {
    /// Continue from this checkpoint (of the same scenario) instead of starting at rest.
    pub resume: Option<&'a Checkpoint>,
    /// Stop once the frame with this index has been recorded (before the scenario's end).
    pub stop_after_frame: Option<usize>,
    /// Stop once this flag is set (by a signal handler): polled between the stages of every
    /// step ([`StopRequest`]), so a run stops within one stage, abandoning the step being taken
    /// (its state stays at the step's start); the checkpoint is that of the last recorded
    /// frame.
    pub stop: Option<&'a AtomicBool>,
    /// The most steps the run may take (`None`: [`DEFAULT_MAX_STEPS`]); a scenario that needs
    /// more is refused before it starts.
    pub max_steps: Option<u64>,
}

/// The default cap on the steps of a run: 10⁸ steps are ≈ 5 h at 100 bodies (≈ 180 µs per
/// step) and ≈ 30 GB of outputs at one frame per 10 steps; more needs an explicit cap.
pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;

/// How a run ended.
#[derive(Debug)]
pub enum RunEnd {
    /// The scenario's whole duration was simulated.
    Completed,
    /// Stopped after the frame given by [`RunOptions::stop_after_frame`], or after a step once
    /// the flag [`RunOptions::stop`] was set (then the steps since the last frame are not
    /// recorded: a resume takes them again from the checkpoint).
    Interrupted,
    /// A tie phase did not tie its knot in its attempts; the outputs hold every frame.
    TieFailed(hagfish_control::TieFailure),
    /// A step failed or was rejected (non-finite state, failed solve, penetration or limit
    /// excess beyond [`hagfish_sim::StepAcceptance`], …) even as substeps down to h/2^k; the
    /// outputs hold every frame before.
    Diverged {
        /// What failed.
        error: SimError,
        /// The run at the start of the failed step (its `files` are empty).
        at: Box<Checkpoint>,
    },
}

/// A run's summary, how it ended, and its final state.
#[derive(Debug)]
pub struct RunOutcome {
    /// Steps, frames, knots, maxima, timings.
    pub summary: RunSummary,
    /// How it ended.
    pub end: RunEnd,
    /// The state at the end (before the failed step if it diverged).
    pub state: State,
}

impl RunOutcome {
    /// The summary of a run that did not diverge, or the error that made it diverge.
    pub fn finished(self) -> Result<RunSummary, RunError> {
        match self.end {
            RunEnd::Diverged { error, .. } => Err(error.into()),
            RunEnd::TieFailed(failure) => Err(RunError::TieFailed(failure)),
            RunEnd::Completed | RunEnd::Interrupted => Ok(self.summary),
        }
    }
}

/// Runs `loaded` to its duration (or until `options` stops it), giving every recorded frame
/// and then its checkpoint to `sink` and calling `progress` after each. Errors are those of
/// setting up, resuming and recording; a failed step ends the run as [`RunEnd::Diverged`].
pub fn run(
    loaded: &LoadedScenario,
    options: RunOptions<'_>,
    sink: &mut dyn FrameSink,
    progress: &mut dyn FnMut(&Progress<'_>),
) -> Result<RunOutcome, RunError> {
    PreparedRun::new(loaded, options.max_steps)?.run(loaded, options, sink, progress)
}

/// A run checked and built, before anything is recorded: every refusal that does not depend
/// on a run directory (the step cap, a duration too long for it, a body too large for the
/// memory, a world that cannot be built) is made by [`PreparedRun::new`], so a caller can
/// make it before it touches its outputs.
#[derive(Debug)]
pub struct PreparedRun {
    world: World,
    controller: PhasedController,
    steps: u64,
}

impl PreparedRun {
    /// Checks the steps `loaded` needs against `max_steps` (`None`: [`DEFAULT_MAX_STEPS`])
    /// and builds its world and controller (which checks the memory the step needs).
    ///
    /// # Errors
    /// [`RunError::TooManySteps`] first (no world is built then), else the errors of
    /// [`LoadedScenario::build`].
    pub fn new(loaded: &LoadedScenario, max_steps: Option<u64>) -> Result<Self, RunError> {
        let scenario = &loaded.scenario;
        let steps = (scenario.duration_s / scenario.time_step_s).round();
        let cap = max_steps.unwrap_or(DEFAULT_MAX_STEPS);
        if steps.is_nan() || steps > cap as f64 {
            return Err(RunError::TooManySteps { steps, cap });
        }
        let (world, controller) = loaded.build()?;
        Ok(Self { world, controller, steps: steps as u64 })
    }

    /// The body model of the run.
    pub fn model(&self) -> &hagfish_tree::Model {
        self.world.model()
    }

    /// Runs it as [`run`] does (`options.max_steps` was applied by [`PreparedRun::new`]);
    /// `loaded` must be the scenario it was prepared from.
    ///
    /// # Errors
    /// Those of resuming from `options.resume` and of recording into `sink`.
    pub fn run(
        self,
        loaded: &LoadedScenario,
        options: RunOptions<'_>,
        sink: &mut dyn FrameSink,
        progress: &mut dyn FnMut(&Progress<'_>),
    ) -> Result<RunOutcome, RunError> {
        let Self { mut world, mut controller, steps } = self;
        let mut centres = Vec::new();
        world.body_centres(&mut centres);
        let arcs = dof_arc_lengths(&centres, world.model().dof_joint());
        let mut summary = RunSummary {
            force_field: ForceFieldLog::new(dof_labels(world.model()), arcs),
            ..RunSummary::default()
        };
        if let Some(checkpoint) = options.resume {
            let multipliers =
                checkpoint.warm_start.multipliers().ok_or_else(|| RunError::Checkpoint {
                    path: CHECKPOINT_FILE.into(),
                    reason: "the warm start's values are not three a row".into(),
                })?;
            world.resume(checkpoint.state(), checkpoint.steps, &multipliers)?;
            controller.restore(&checkpoint.controller).map_err(|e| RunError::Checkpoint {
                path: CHECKPOINT_FILE.into(),
                reason: e.to_string(),
            })?;
            summary.frames = checkpoint.frames;
            summary.maxima = checkpoint.maxima;
            summary.substepped_steps = checkpoint.substepped_steps;
            summary.max_substeps = checkpoint.max_substeps;
            summary.resolved_steps = checkpoint.resolved_steps;
        }
        summary.max_substeps = summary.max_substeps.max(1);
        stepping(world, controller, steps, summary, (loaded, options), sink, progress)
    }
}

/// The loop of [`PreparedRun::run`]: steps, frames and the end.
fn stepping(
    mut world: World,
    mut controller: PhasedController,
    steps: u64,
    mut summary: RunSummary,
    (loaded, options): (&LoadedScenario, RunOptions<'_>),
    sink: &mut dyn FrameSink,
    progress: &mut dyn FnMut(&Progress<'_>),
) -> Result<RunOutcome, RunError> {
    let scenario = &loaded.scenario;
    let record_every = whole_steps(scenario.record_every_s, scenario.time_step_s);
    let observe_every = whole_steps(scenario.observe_every_s, scenario.time_step_s);
    let mut recording = Recording::new(&world, loaded);
    // Frame 0 is the initial state, and the first observation; a resumed run recorded its
    // last frame (and made any observation due at it) before it stopped.
    let mut record = options.resume.is_none();
    let mut observe = record;
    let end = loop {
        if record || observe {
            recording.analyse_knot(&mut world);
            if observe {
                recording.observe(&world, &mut controller);
            }
            // A failed tie ends the run on a frame of the state it failed in.
            let tie_failure = controller.tie_failure();
            if record || tie_failure.is_some() {
                recording.frame(
                    &mut world,
                    &mut controller,
                    &mut summary,
                    sink,
                    progress,
                    scenario,
                )?;
                let stop = options.stop_after_frame.is_some_and(|k| summary.frames > k)
                    || options.stop.is_some_and(|flag| flag.load(Ordering::Relaxed));
                if stop && world.steps() < steps && tie_failure.is_none() {
                    break RunEnd::Interrupted;
                }
            }
            if let Some(failure) = tie_failure {
                break RunEnd::TieFailed(failure);
            }
        }
        let phases_over = scenario.end_after_phases && controller.finished();
        if world.steps() >= steps || phases_over {
            break RunEnd::Completed;
        }
        // Joint loads are recorded, not used by the step: they are computed only for a step
        // that may end on a frame (every step when the phases may end the run; an
        // observation, as a failed tie is recorded there).
        let next = world.steps() + 1;
        world.set_internal_forces_due(
            scenario.end_after_phases
                || next.is_multiple_of(record_every)
                || next.is_multiple_of(observe_every),
        );
        let stop = StopRequest::new(options.stop);
        match world.advance(&mut controller, &mut recording.tally, stop) {
            StepOutcome::Accepted => {}
            StepOutcome::ResolvedContacts => summary.resolved_steps += 1,
            StepOutcome::Substeps { divisions } => {
                summary.substepped_steps += 1;
                summary.max_substeps = summary.max_substeps.max(divisions);
            }
            // Abandoned at a stage boundary: the state is the step's start, the checkpoint
            // that of the last frame.
            StepOutcome::Stopped => break RunEnd::Interrupted,
            StepOutcome::Failed(error) => {
                let at = Box::new(recording.checkpoint(&world, &controller, &summary));
                break RunEnd::Diverged { error, at };
            }
        }
        let phases_over = scenario.end_after_phases && controller.finished();
        record = world.steps().is_multiple_of(record_every) || phases_over;
        observe = world.steps().is_multiple_of(observe_every);
        if !record && options.stop.is_some_and(|flag| flag.load(Ordering::Relaxed)) {
            break RunEnd::Interrupted;
        }
    };
    summary.steps = world.steps();
    summary.timings = recording.tally.timings;
    summary.unfinished_phase = controller.unfinished_phase();
    summary.resolved_cluster_bodies = world.options().resolved_cluster_radius(world.model());
    Ok(RunOutcome { summary, end, state: world.state().clone() })
}

/// An interval of `interval_s` as a whole number of steps of `time_step_s`: the nearest, at
/// least one.
fn whole_steps(interval_s: f64, time_step_s: f64) -> u64 {
    ((interval_s / time_step_s).round() as u64).max(1)
}

/// The scratch of recording frames: buffers, labels, and what the steps since the previous
/// frame add up to.
struct Recording {
    hash: String,
    body_hash: String,
    referenced_files_hash: String,
    radii: Vec<f64>,
    body_length_cm: f64,
    knot_options: KnotOptions,
    knots: KnotAnalyser,
    /// The knot analysis of the current state, by [`Recording::analyse_knot`].
    knot: Option<KnotReport>,
    centres: Vec<DVec3>,
    labels: Vec<DofLabel>,
    /// The forces, maxima and last report of the steps since the previous frame, and the
    /// stage timings of the whole call.
    tally: StepTally,
}

impl Recording {
    fn new(world: &World, loaded: &LoadedScenario) -> Self {
        Self {
            hash: loaded.hash(),
            body_hash: loaded.body_hash.clone(),
            referenced_files_hash: loaded.referenced_files_hash.clone(),
            radii: world.model().bodies().iter().map(|b| b.radius).collect(),
            body_length_cm: world.model().bodies().iter().map(|b| b.length).sum(),
            knot_options: KnotOptions::default(),
            knots: KnotAnalyser::default(),
            knot: None,
            centres: Vec::with_capacity(world.model().body_count()),
            labels: dof_labels(world.model()),
            tally: StepTally::default(),
        }
    }

    /// Analyses the knot of the current state into `self.knot` (`None` where the analysis
    /// fails, e.g. too few bodies), leaving the body centres in `self.centres`.
    fn analyse_knot(&mut self, world: &mut World) {
        world.body_centres(&mut self.centres);
        self.knot = self.knots.analyse(&self.centres, &self.knot_options).ok();
    }

    /// Gives the controller what the knot analysis of the current state
    /// ([`Self::analyse_knot`]) shows: type, handedness and knotted core, which end a tie and
    /// the core-based end conditions.
    fn observe(&self, world: &World, controller: &mut PhasedController) {
        let knot = self.knot.as_ref();
        let name = knot.map(|k| k.knot.to_string());
        let observed = knot.zip(name.as_deref()).map(|(k, name)| {
            let core = KnotCore::of(k, &self.centres, &self.radii, self.body_length_cm);
            KnotObservation {
                name,
                agreement: k.agreement,
                right_handed: k.right_handed(),
                core_start_l: core.map(|core| core.of_body_length(core.start_cm)),
                core_length_d: core.map(|core| core.length_in_diameters()),
            }
        });
        controller.observe_knot(world.state().t, observed);
    }

    /// Records the current state as the next frame, with its knot analysis
    /// ([`Self::analyse_knot`], run first), then hands its checkpoint to the sink.
    fn frame(
        &mut self,
        world: &mut World,
        controller: &mut PhasedController,
        summary: &mut RunSummary,
        sink: &mut dyn FrameSink,
        progress: &mut dyn FnMut(&Progress<'_>),
        scenario: &Scenario,
    ) -> Result<(), RunError> {
        let knot = self.knot.take();
        let dofs = world.model().dof_count();
        self.tally.forces.finish_interval(dofs, world.options().time_step);
        let data = world.data();
        let span = KnotSpan::of(&data.self_contacts, &data.centreline);
        let phase = controller.phase_name();
        summary.force_field.push(
            world.state().t,
            phase,
            span,
            self.tally.forces.group(RowGroup::Thigmo),
        );
        sink.record(&Frame {
            index: summary.frames,
            time: world.state().t,
            phase,
            state: world.state(),
            centres: &self.centres,
            step: &self.tally.last_report,
            maxima: &self.tally.maxima,
            knot: knot.as_ref(),
            radii: &self.radii,
            body_length_cm: self.body_length_cm,
            span,
            contacts: &data.self_contacts,
            centreline: &data.centreline,
            labels: &self.labels,
            forces: &self.tally.forces,
            internal: &data.internal.loads,
            grip: data.internal.grip,
        })?;
        summary.maxima.merge(&self.tally.maxima);
        self.tally.maxima = IntervalMaxima::default();
        self.tally.forces.clear();
        summary.frames += 1;
        summary.steps = world.steps();
        sink.checkpoint(&mut self.checkpoint(world, controller, summary))?;
        progress(&Progress {
            time: world.state().t,
            duration: scenario.duration_s,
            ends_with_phases: scenario.end_after_phases,
            frames: summary.frames,
            steps: world.steps(),
            knot: knot.as_ref(),
            phase: controller.phase_name(),
        });
        summary.knots.push(KnotSample { time: world.state().t, knot });
        Ok(())
    }

    /// The checkpoint of the run as it is (no file lengths: the sink adds them).
    fn checkpoint(
        &self,
        world: &World,
        controller: &PhasedController,
        summary: &RunSummary,
    ) -> Checkpoint {
        let state = world.state();
        let mut maxima = summary.maxima;
        maxima.merge(&self.tally.maxima);
        Checkpoint {
            format: CHECKPOINT_FORMAT,
            scenario_hash: self.hash.clone(),
            body_hash: self.body_hash.clone(),
            referenced_files_hash: Some(self.referenced_files_hash.clone()),
            frames: summary.frames,
            steps: world.steps(),
            t: ExactF64s(vec![state.t]),
            q: ExactF64s(state.q.clone()),
            qdot: ExactF64s(state.qdot.clone()),
            warm_start: CarriedMultipliers::new(world.data().warm_start.carried()),
            controller: controller.state(),
            maxima,
            substepped_steps: summary.substepped_steps,
            max_substeps: summary.max_substeps,
            resolved_steps: summary.resolved_steps,
            files: Vec::new(),
        }
    }
}
