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
}
