//! Errors of reading, overriding and checking a scenario, and of building its world.

use hagfish_sim::SimError;

/// What can stop a scenario from loading or building: each error of a file at its
/// `file:line:column`, an override with the value given.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// A scenario or biometrics file is unreadable or invalid (message has file:line:column).
    #[error(transparent)]
    DataFile(#[from] hagfish_anatomy::AnatomyError),
    /// The scenario gives a skin to a body that is not a hagfish (a rod has none).
    #[error("{at}: skin: a skin needs a hagfish body, and this body file is a rod")]
    SkinOnRod {
        /// Where the scenario gives the skin.
        at: hagfish_anatomy::Origin,
    },
    /// The body file a scenario names cannot be read (the position is the scenario's `body`).
    #[error("{at}: body: {source}")]
    BodyFile {
        /// Where the scenario names the body file.
        at: hagfish_anatomy::Origin,
        /// The underlying error.
        source: Box<hagfish_anatomy::AnatomyError>,
    },
    /// A modal force space's file cannot give its basis: unreadable or malformed, no modes of
    /// the kind, fewer modes than asked, or shapes that are rank-deficient on this body (the
    /// position is the space's `file` or `modes`).
    #[error("{at}: {reason}")]
    ModeFile {
        /// Where the scenario names the file or the number of modes.
        at: hagfish_anatomy::Origin,
        /// What is wrong.
        reason: String,
    },
    /// The body's model could not be built.
    #[error("building the model: {0}")]
    Model(#[from] hagfish_tree::TreeError),
    /// A `--set PATH=VALUE` override that cannot be applied (`overrides.rs`).
    #[error("--set {given}: {reason}")]
    Override {
        /// The override as given.
        given: String,
        /// Why it cannot be applied.
        reason: String,
    },
    /// The scenario with its overrides applied fails a check (the location is in the
    /// overridden scenario, as its run directory's `scenario.ron` records it).
    #[error("with --set {overrides}: {source}")]
    Overridden {
        /// The overrides, as given.
        overrides: String,
        /// The failed check.
        source: Box<ScenarioError>,
    },
    /// Building the scenario's world, or stepping it (`LoadedScenario::build_at`), failed.
    #[error(transparent)]
    Sim(#[from] SimError),
}
