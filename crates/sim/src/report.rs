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
    /// Deepest self-contact penetration at the start of the step, `max(0, −gap)` (cm).
    pub max_self_penetration: f64,
    /// The deepest self penetration relative to the local radius `(r_a + r_b)/2`
    /// (dimensionless).
    pub max_self_penetration_relative: f64,
    /// Deepest wall penetration at the start of the step (cm).
    pub max_wall_penetration: f64,
    /// Self-contact bounds raised by the contact predictor, summed over the step's re-solves.
    pub predicted_contact_rows: usize,
    /// Wall-clock time spent in each stage (not part of the simulation's results).
    pub timings: StageTimings,
}

/// Seconds of wall-clock time per stage of one step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StageTimings {
    /// Frames, axes, twists.
    pub kinematics: f64,
    /// Centreline, broad and narrow phase, wall.
    pub detect_contacts: f64,
    /// The controller.
    pub control: f64,
    /// M̃, momentum, generalized force.
    pub dynamics: f64,
    /// Constraint rows.
    pub build_rows: f64,
    /// Every velocity solve of the step, with the velocity-product refreshes and added rows.
    pub solve: f64,
    /// The load each joint transmits (backward pass over the tree).
    pub internal_forces: f64,
    /// Position update.
    pub integrate: f64,
    /// The result's kinematics and contacts (taken over by the next step) and its judgement.
    pub check: f64,
}

impl StageTimings {
    /// Adds another step's timings.
    pub fn accumulate(&mut self, other: &StageTimings) {
        self.kinematics += other.kinematics;
        self.detect_contacts += other.detect_contacts;
        self.control += other.control;
        self.dynamics += other.dynamics;
        self.build_rows += other.build_rows;
        self.solve += other.solve;
        self.internal_forces += other.internal_forces;
        self.integrate += other.integrate;
        self.check += other.check;
    }

    /// The named stages and their seconds, in pipeline order.
    pub fn stages(&self) -> [(&'static str, f64); 9] {
        [
            ("kinematics", self.kinematics),
            ("detect_contacts", self.detect_contacts),
            ("control", self.control),
            ("dynamics", self.dynamics),
            ("build_rows", self.build_rows),
            ("solve", self.solve),
            ("internal_forces", self.internal_forces),
            ("integrate", self.integrate),
            ("check", self.check),
        ]
    }

    /// Sum of all stages (s).
    pub fn total(&self) -> f64 {
        self.kinematics
            + self.detect_contacts
            + self.control
            + self.dynamics
            + self.build_rows
            + self.solve
            + self.internal_forces
            + self.integrate
            + self.check
    }
}
