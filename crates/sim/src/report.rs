//! What one step reports: the solver's outcome, contact counts and penetration.

use hagfish_geometry::DetectionReport;
use hagfish_solver::SolveReport;

/// The report of the last step (see [`crate::World::step`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Index of the step (0 for the first).
    pub step: u64,
    /// Simulation time at the start of the step (s).
    pub time: f64,
    /// The velocity solve: path, status, iterations, residuals, rows per group, slack.
    pub solve: SolveReport,
    /// Self-contact detection counts (candidates, Newton failures, merged duplicates).
    pub detection: DetectionReport,
    /// Number of self contacts after merging.
    pub self_contacts: usize,
    /// Number of bodies in contact with the wall (within the margin).
    pub wall_contacts: usize,
    /// Deepest self-contact penetration at the start of the step, `max(0, −gap)` (cm): of
    /// the cores where the body has a skin (docs/physics.md, "Skin").
    pub max_self_penetration: f64,
    /// The deepest self penetration relative to the local (core) radius `(r_a + r_b)/2`
    /// (dimensionless).
    pub max_self_penetration_relative: f64,
    /// The deepest compression of the skins at a self contact at the start of the step, as a
    /// fraction of their thickness `t_a + t_b` (0 without a skin, 1 where the cores touch).
    pub max_skin_compression: f64,
    /// Deepest wall penetration at the start of the step (cm).
    pub max_wall_penetration: f64,
    /// Self-contact bounds raised by the contact predictor, summed over the step's re-solves.
    pub predicted_contact_rows: usize,
    /// Wall-clock time spent in each stage (not part of the simulation's results).
    pub timings: StageTimings,
}

/// The stages of a step, in pipeline order ([`crate::pipeline`]): the keys of its timings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Frames, axes, twists.
    Kinematics,
    /// Centreline, broad and narrow phase, wall (or taking over the carried contacts).
    DetectContacts,
    /// The controller.
    Control,
    /// M̃, momentum, generalized force.
    Dynamics,
    /// Constraint rows.
    BuildRows,
    /// Every velocity solve of the step, with the velocity-product refreshes and added rows.
    Solve,
    /// The load each joint transmits (backward pass over the tree).
    InternalForces,
    /// Position update.
    Integrate,
    /// The result's kinematics and contacts (taken over by the next step) and its judgement.
    Check,
}

impl Stage {
    /// Every stage, in pipeline order.
    pub const ALL: [Stage; 9] = [
        Stage::Kinematics,
        Stage::DetectContacts,
        Stage::Control,
        Stage::Dynamics,
        Stage::BuildRows,
        Stage::Solve,
        Stage::InternalForces,
        Stage::Integrate,
        Stage::Check,
    ];

    /// The stage's name, as the pipeline's function (`detect_contacts`, …).
    pub fn name(self) -> &'static str {
        match self {
            Stage::Kinematics => "kinematics",
            Stage::DetectContacts => "detect_contacts",
            Stage::Control => "control",
            Stage::Dynamics => "dynamics",
            Stage::BuildRows => "build_rows",
            Stage::Solve => "solve",
            Stage::InternalForces => "internal_forces",
            Stage::Integrate => "integrate",
            Stage::Check => "check",
        }
    }
}

/// Seconds of wall-clock time per stage of one step (or summed over steps), keyed by
/// [`Stage`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StageTimings {
    seconds: [f64; Stage::ALL.len()],
}

impl StageTimings {
    /// The seconds of `stage`.
    pub fn get(&self, stage: Stage) -> f64 {
        self.seconds[stage as usize]
    }

    /// Adds `seconds` to `stage`.
    pub fn add(&mut self, stage: Stage, seconds: f64) {
        self.seconds[stage as usize] += seconds;
    }

    /// Adds another step's timings.
    pub fn accumulate(&mut self, other: &StageTimings) {
        for (mine, theirs) in self.seconds.iter_mut().zip(other.seconds) {
            *mine += theirs;
        }
    }

    /// The named stages and their seconds, in pipeline order.
    pub fn stages(&self) -> [(&'static str, f64); Stage::ALL.len()] {
        Stage::ALL.map(|stage| (stage.name(), self.get(stage)))
    }

    /// Sum of all stages (s).
    pub fn total(&self) -> f64 {
        self.seconds.iter().sum()
    }
}

/// The clock of one step's stages: each [`StageClock::lap`] charges the time since the last
/// one to a stage.
#[derive(Debug)]
pub(crate) struct StageClock {
    last: std::time::Instant,
    timings: StageTimings,
}

impl StageClock {
    /// A clock started now, with no time charged.
    pub(crate) fn start() -> Self {
        Self { last: std::time::Instant::now(), timings: StageTimings::default() }
    }

    /// Charges the time since the previous lap (or the start) to `stage`.
    pub(crate) fn lap(&mut self, stage: Stage) {
        let now = std::time::Instant::now();
        self.timings.add(stage, (now - self.last).as_secs_f64());
        self.last = now;
    }

    /// The time charged to each stage.
    pub(crate) fn timings(&self) -> StageTimings {
        self.timings
    }
}
