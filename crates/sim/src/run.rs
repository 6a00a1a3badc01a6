//! Running a scenario: step the world, record frames, check the knot, report progress, and
//! hand a checkpoint to the sink after every frame. A run starts at rest or from a
//! [`Checkpoint`], and ends completed, interrupted (asked to stop after a frame) or diverged
//! (a step failed: the state is kept as it was before that step).

use std::sync::atomic::{AtomicBool, Ordering};

use glam::DVec3;
use hagfish_control::{KnotSpan, PhasedController};
use hagfish_knots::{KnotAnalyser, KnotOptions, KnotReport};
use hagfish_solver::RowGroup;
use hagfish_tree::State;

use crate::checkpoint::{CHECKPOINT_FILE, CHECKPOINT_FORMAT, Checkpoint, ExactF64s};
use crate::error::SimError;
use crate::force_field::ForceFieldLog;
use crate::forces::{GroupForces, dof_labels};
use crate::recorder::{Frame, FrameSink, IntervalMaxima};
use crate::report::{StageTimings, StepReport};
use crate::scenario::LoadedScenario;
use crate::world::World;

/// Progress of a run, given to the caller after every recorded frame.
#[derive(Clone, Copy, Debug)]
pub struct Progress<'a> {
    /// Simulated time (s).
    pub time: f64,
    /// Total simulated time of the run (s).
    pub duration: f64,
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
}

/// Where a run starts and when it stops early.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOptions<'a> {
    /// Continue from this checkpoint (of the same scenario) instead of starting at rest.
    pub resume: Option<&'a Checkpoint>,
    /// Stop once the frame with this index has been recorded (before the scenario's end).
    pub stop_after_frame: Option<usize>,
    /// Stop after the next recorded frame once this flag is set (by a signal handler).
    pub stop: Option<&'a AtomicBool>,
}

/// How a run ended.
#[derive(Debug)]
pub enum RunEnd {
    /// The scenario's whole duration was simulated.
    Completed,
    /// Stopped after the frame given by [`RunOptions::stop_after_frame`] or after the flag
    /// [`RunOptions::stop`] was set.
    Interrupted,
    /// A step failed (non-finite state, failed solve, …); the outputs hold every frame before.
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
    pub fn finished(self) -> Result<RunSummary, SimError> {
        match self.end {
            RunEnd::Diverged { error, .. } => Err(error),
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
) -> Result<RunOutcome, SimError> {
    let (mut world, mut controller) = loaded.build()?;
    let mut summary = RunSummary {
        force_field: ForceFieldLog::new(dof_labels(world.model()), dof_arc_lengths(&mut world)),
        ..RunSummary::default()
    };
    if let Some(checkpoint) = options.resume {
        world.resume(checkpoint.state(), checkpoint.steps, &checkpoint.multipliers.0)?;
        controller.restore(&checkpoint.controller).map_err(|e| SimError::Checkpoint {
            path: CHECKPOINT_FILE.into(),
            reason: e.to_string(),
        })?;
        summary.frames = checkpoint.frames;
        summary.maxima = checkpoint.maxima;
    }
    let scenario = &loaded.scenario;
    let steps = (scenario.duration_s / scenario.time_step_s).round() as u64;
    let record_every = ((scenario.record_every_s / scenario.time_step_s).round() as u64).max(1);
    let mut recording = Recording::new(&world, loaded.hash());
    // Frame 0 is the initial state; a resumed run recorded its last frame before it stopped.
    let mut record = options.resume.is_none();
    let end = loop {
        if record {
            recording.frame(
                &mut world,
                &controller,
                &mut summary,
                sink,
                progress,
                scenario.duration_s,
            )?;
            let stop = options.stop_after_frame.is_some_and(|k| summary.frames > k)
                || options.stop.is_some_and(|flag| flag.load(Ordering::Relaxed));
            if stop && world.steps() < steps {
                break RunEnd::Interrupted;
            }
        }
        if world.steps() >= steps {
            break RunEnd::Completed;
        }
        match world.step(&mut controller) {
            Ok(report) => {
                recording.last_report = *report;
                recording.forces.add_step(world.data(), world.model().dof_count());
                recording.maxima.include(&recording.last_report, world.max_limit_excess());
                summary.timings.accumulate(&recording.last_report.timings);
            }
            Err(error) => {
                let at = Box::new(recording.checkpoint(&world, &controller, &summary));
                break RunEnd::Diverged { error, at };
            }
        }
        record = world.steps() % record_every == 0;
    };
    summary.steps = world.steps();
    Ok(RunOutcome { summary, end, state: world.state().clone() })
}

/// The scratch of recording frames: buffers, labels, the latest step report and the maxima
/// since the previous frame.
struct Recording {
    hash: String,
    knot_options: KnotOptions,
    knots: KnotAnalyser,
    centres: Vec<DVec3>,
    labels: Vec<crate::forces::DofLabel>,
    forces: GroupForces,
    last_report: StepReport,
    maxima: IntervalMaxima,
}

impl Recording {
    fn new(world: &World, hash: String) -> Self {
        Self {
            hash,
            knot_options: KnotOptions::default(),
            knots: KnotAnalyser::default(),
            centres: Vec::with_capacity(world.model().body_count()),
            labels: dof_labels(world.model()),
            forces: GroupForces::default(),
            last_report: StepReport::default(),
            maxima: IntervalMaxima::default(),
        }
    }

    /// Records the current state as the next frame, then hands its checkpoint to the sink.
    fn frame(
        &mut self,
        world: &mut World,
        controller: &PhasedController,
        summary: &mut RunSummary,
        sink: &mut dyn FrameSink,
        progress: &mut dyn FnMut(&Progress<'_>),
        duration: f64,
    ) -> Result<(), SimError> {
        world.body_centres(&mut self.centres);
        let knot = self.knots.analyse(&self.centres, &self.knot_options).ok();
        let dofs = world.model().dof_count();
        self.forces.finish_interval(dofs, world.options().time_step);
        let data = world.data();
        let span = KnotSpan::of(&data.self_contacts, &data.centreline);
        let phase = controller.phase_name();
        summary.force_field.push(world.state().t, phase, span, self.forces.group(RowGroup::Thigmo));
        sink.record(&Frame {
            index: summary.frames,
            time: world.state().t,
            phase,
            state: world.state(),
            centres: &self.centres,
            step: &self.last_report,
            maxima: &self.maxima,
            knot: knot.as_ref(),
            span,
            contacts: &data.self_contacts,
            centreline: &data.centreline,
            labels: &self.labels,
            forces: &self.forces,
        })?;
        summary.maxima.merge(&self.maxima);
        self.maxima = IntervalMaxima::default();
        self.forces.clear();
        summary.frames += 1;
        summary.steps = world.steps();
        sink.checkpoint(&mut self.checkpoint(world, controller, summary))?;
        progress(&Progress {
            time: world.state().t,
            duration,
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
        maxima.merge(&self.maxima);
        Checkpoint {
            format: CHECKPOINT_FORMAT,
            scenario_hash: self.hash.clone(),
            frames: summary.frames,
            steps: world.steps(),
            t: ExactF64s(vec![state.t]),
            q: ExactF64s(state.q.clone()),
            qdot: ExactF64s(state.qdot.clone()),
            multipliers: ExactF64s(world.data().solver.multipliers().to_vec()),
            controller: controller.state(),
            maxima,
            files: Vec::new(),
        }
    }
}

/// Arc length of each DOF's joint from the head body's centre (cm), read off the body centres
/// of `world` at rest (straight): tree joint i sits halfway between centres i − 1 and i (joint
/// 0 at the wall). This is the arc-length convention of [`KnotSpan`].
fn dof_arc_lengths(world: &mut World) -> Vec<f64> {
    let mut centres = Vec::new();
    world.body_centres(&mut centres);
    let joint_arc = |i: usize| match i {
        0 => -centres[0].length(),
        _ => (0.5 * (centres[i - 1] + centres[i]) - centres[0]).length(),
    };
    world.model().dof_joint().iter().map(|&joint| joint_arc(joint)).collect()
}
