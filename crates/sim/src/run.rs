//! Running a scenario: step the world, record frames, check the knot, report progress.

use glam::DVec3;
use hagfish_control::KnotSpan;
use hagfish_knots::{KnotOptions, KnotReport, analyse_knot};
use hagfish_tree::State;

use crate::error::SimError;
use crate::forces::{GroupForces, dof_labels};
use crate::recorder::{Frame, FrameSink, IntervalMaxima};
use crate::report::{StageTimings, StepReport};
use crate::scenario::LoadedScenario;

/// Progress of a run, given to the caller after every recorded frame.
#[derive(Clone, Copy, Debug)]
pub struct Progress<'a> {
    /// Simulated time (s).
    pub time: f64,
    /// Total simulated time of the run (s).
    pub duration: f64,
    /// Frames recorded so far.
    pub frames: usize,
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

/// What a finished run reports.
#[derive(Clone, Debug, Default)]
pub struct RunSummary {
    /// Steps taken.
    pub steps: u64,
    /// Frames recorded.
    pub frames: usize,
    /// Knot analysis of every frame.
    pub knots: Vec<KnotSample>,
    /// Worst penetrations and limit excess over the whole run.
    pub maxima: IntervalMaxima,
    /// Wall-clock seconds per stage, summed over all steps.
    pub timings: StageTimings,
    /// The state at the end of the run (`None` only before a run has filled the summary).
    pub final_state: Option<State>,
}

/// Runs `loaded` to its duration, giving every recorded frame to `sink` and calling
/// `progress` after each.
pub fn run(
    loaded: &LoadedScenario,
    sink: &mut dyn FrameSink,
    progress: &mut dyn FnMut(&Progress<'_>),
) -> Result<RunSummary, SimError> {
    let (mut world, mut controller) = loaded.build()?;
    let scenario = &loaded.scenario;
    let steps = (scenario.duration_s / scenario.time_step_s).round() as u64;
    let record_every = ((scenario.record_every_s / scenario.time_step_s).round() as u64).max(1);
    let knot_options = KnotOptions::default();
    let mut centres: Vec<DVec3> = Vec::with_capacity(world.model().body_count());
    let mut summary = RunSummary::default();
    let mut last_report = StepReport::default();
    let mut maxima = IntervalMaxima::default();
    let labels = dof_labels(world.model());
    let mut forces = GroupForces::default();
    for step in 0..=steps {
        if step > 0 {
            last_report = *world.step(&mut controller)?;
            maxima.include(&last_report, world.max_limit_excess());
            summary.timings.accumulate(&last_report.timings);
        }
        if step % record_every != 0 {
            continue;
        }
        world.body_centres(&mut centres);
        let knot = analyse_knot(&centres, &knot_options).ok();
        forces.fill(world.data(), world.model().dof_count(), scenario.time_step_s);
        let frame = Frame {
            index: summary.frames,
            time: world.state().t,
            phase: controller.phase_name(),
            centres: &centres,
            step: &last_report,
            maxima: &maxima,
            knot: knot.as_ref(),
            span: KnotSpan::of(&world.data().self_contacts, &world.data().centreline),
            labels: &labels,
            forces: &forces,
        };
        sink.record(&frame)?;
        summary.maxima.merge(&maxima);
        maxima = IntervalMaxima::default();
        summary.frames += 1;
        progress(&Progress {
            time: world.state().t,
            duration: scenario.duration_s,
            frames: summary.frames,
            knot: knot.as_ref(),
            phase: controller.phase_name(),
        });
        summary.knots.push(KnotSample { time: world.state().t, knot });
    }
    summary.steps = world.steps();
    summary.final_state = Some(world.state().clone());
    Ok(summary)
}
