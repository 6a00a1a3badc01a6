//! Running a scenario: step the world, record frames, check the knot, report progress.

use std::path::Path;

use glam::DVec3;
use hagfish_knots::{KnotOptions, KnotReport, analyse_knot};

use crate::error::SimError;
use crate::recorder::{Frame, Recorder};
use crate::report::StepReport;
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
    /// Largest self penetration relative to the local radius sum over the run.
    pub max_self_penetration_relative: f64,
    /// Largest wall penetration (cm).
    pub max_wall_penetration: f64,
    /// Largest excess of a joint over its limit (rad).
    pub max_limit_excess: f64,
}

/// Runs `loaded` to its duration, writing outputs into `out_dir`, calling `progress` after
/// each recorded frame.
pub fn run(
    loaded: &LoadedScenario,
    out_dir: &Path,
    progress: &mut dyn FnMut(&Progress<'_>),
) -> Result<RunSummary, SimError> {
    let (mut world, mut controller) = loaded.build()?;
    let scenario = &loaded.scenario;
    let mut recorder = Recorder::create(out_dir)?;
    let steps = (scenario.duration_s / scenario.time_step_s).round() as u64;
    let record_every = ((scenario.record_every_s / scenario.time_step_s).round() as u64).max(1);
    let knot_options = KnotOptions::default();
    let mut centres: Vec<DVec3> = Vec::with_capacity(world.model().body_count());
    let mut summary = RunSummary::default();
    let mut last_report = StepReport::default();
    for step in 0..=steps {
        if step > 0 {
            last_report = *world.step(&mut controller)?;
            summary.max_self_penetration_relative =
                summary.max_self_penetration_relative.max(last_report.max_self_penetration_relative);
            summary.max_wall_penetration = summary.max_wall_penetration.max(last_report.max_wall_penetration);
            summary.max_limit_excess = summary.max_limit_excess.max(world.max_limit_excess());
        }
        if step % record_every != 0 {
            continue;
        }
        world.body_centres(&mut centres);
        let knot = analyse_knot(&centres, &knot_options).ok();
        let frame = Frame {
            index: summary.frames,
            time: world.state().t,
            phase: controller.phase_name(),
            centres: &centres,
            step: &last_report,
            knot: knot.as_ref(),
        };
        recorder.record(&frame)?;
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
    Ok(summary)
}
