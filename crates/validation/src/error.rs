//! Errors of running a validation case.

/// What can stop a validation case.
#[derive(Debug, thiserror::Error)]
pub enum ValidationError {
    /// The scenario or its body could not be loaded or built.
    #[error(transparent)]
    Load(#[from] hagfish_scenario::ScenarioError),
    /// A step failed.
    #[error(transparent)]
    Sim(#[from] hagfish_sim::SimError),
    /// The scenario is not the kind the case needs.
    #[error("{path}: {reason}")]
    Scenario {
        /// The scenario file.
        path: std::path::PathBuf,
        /// What is missing (e.g. a rod body, a load phase).
        reason: String,
    },
    /// The run ended before its load phase settled.
    #[error("{path}: not settled after {seconds} s (kinetic energy {energy_erg:e} erg)")]
    NotSettled {
        /// The scenario file.
        path: std::path::PathBuf,
        /// Simulated time (s).
        seconds: f64,
        /// Kinetic energy at the end (erg).
        energy_erg: f64,
    },
    /// The knot the run started with is not the one it settled into.
    #[error(
        "{path}: the knot changed from {expected} to {found} while settling (a strand passed \
         through another within one step: try a smaller time step)"
    )]
    KnotChanged {
        /// The scenario file.
        path: std::path::PathBuf,
        /// The knot type of the initial shape.
        expected: String,
        /// The knot type at the end.
        found: String,
    },
}
