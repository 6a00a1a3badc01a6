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
    /// A tie phase's plan file could not be read, or is not a plan (the position is the
    /// knot's `file` in the scenario; the reason names the plan file).
    #[error("{at}: the knot's plan: {reason}")]
    KnotPlanFile {
        /// Where the scenario names the plan file.
        at: hagfish_anatomy::Origin,
        /// What is wrong.
        reason: String,
    },
    /// A follow phase's knot template is unreadable, not a curve, of an unknown knot or too
    /// long for the body (`at`: the template's `file` in the scenario; the reason names the
    /// vertex file).
    #[error("{at}: the knot's template: {reason}")]
    KnotTemplateFile {
        /// Where the scenario names the template file.
        at: hagfish_anatomy::Origin,
        /// What is wrong.
        reason: String,
    },
    /// The vertex file of an initial `Polyline` shape is unreadable or not a curve (`at`: the
    /// shape's `file` in the scenario; the reason names the vertex file and its line).
    #[error("{at}: the initial shape: {reason}")]
    ShapeFile {
        /// Where the scenario names the vertex file.
        at: hagfish_anatomy::Origin,
        /// What is wrong.
        reason: String,
    },
    /// The body's model could not be built.
    #[error("building the model: {0}")]
    Model(#[from] hagfish_tree::TreeError),
    /// A `--set PATH=VALUE` override that cannot be applied (`overrides.rs`).
    #[error("--set {}: {reason}", echo(given))]
    Override {
        /// The override as given.
        given: String,
        /// Why it cannot be applied.
        reason: String,
    },
    /// The scenario with its overrides applied fails a check (the location is in the
    /// overridden scenario, as its run directory's `scenario.ron` records it).
    #[error("with --set {}: {source}", echo(overrides))]
    Overridden {
        /// The overrides, as given.
        overrides: String,
        /// The failed check.
        source: Box<ScenarioError>,
    },
    /// An obstacle of the scenario's `obstacles` list has a bad number (a zero normal or
    /// axis, a radius or half-length not > 0, a point not finite).
    #[error("obstacles[{index}]: {source}")]
    Obstacle {
        /// Its position in the list, from 0.
        index: usize,
        /// What is wrong.
        source: hagfish_geometry::GeometryError,
    },
    /// An obstacle overlaps the head body at the start: the head is held at the wall, so no
    /// step can push it out (the velocity solve has no solution).
    #[error(
        "obstacles[{index}] overlaps the head (body 0, held at the wall) by {depth_cm:.4} cm at          t = 0: no step can push the held head out of it; move the obstacle away from the head"
    )]
    ObstacleOverlapsHead {
        /// Its position in the list, from 0.
        index: usize,
        /// How deep the head's sphere is in it (cm).
        depth_cm: f64,
    },
    /// Building the scenario's world, or stepping it (`LoadedScenario::build_at`), failed.
    #[error(transparent)]
    Sim(#[from] SimError),
}

/// Characters of an echoed text kept from its start, and from its end ([`echo`]).
pub const ECHO_HEAD: usize = 80;
/// See [`ECHO_HEAD`].
pub const ECHO_TAIL: usize = 40;

/// `text` as an error message echoes it: whole up to [`ECHO_HEAD`] + [`ECHO_TAIL`] characters,
/// else its first [`ECHO_HEAD`] and last [`ECHO_TAIL`] characters around the count of those
/// left out, so a 100 kB `--set` value costs a line, not 100 kB (twice: as given and in
/// serde's reason).
pub fn echo(text: &str) -> String {
    let count = text.chars().count();
    if count <= ECHO_HEAD + ECHO_TAIL {
        return text.to_owned();
    }
    let head: String = text.chars().take(ECHO_HEAD).collect();
    let tail: String = text.chars().skip(count - ECHO_TAIL).collect();
    format!("{head}…[{} characters left out]…{tail}", count - ECHO_HEAD - ECHO_TAIL)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_echo_keeps_its_ends_and_counts_the_rest() {
        assert_eq!(echo("short"), "short");
        let long = format!("a{}z", "é".repeat(100_000));
        let shown = echo(&long);
        assert!(shown.starts_with('a') && shown.ends_with('z'), "{shown}");
        assert!(shown.contains("…[99882 characters left out]…"), "{shown}");
        assert!(shown.chars().count() < 200, "{}", shown.len());
    }
}
