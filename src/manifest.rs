//! `manifest.json` of a run directory: what ran (program, version, scenario and its hash),
//! when (UTC, ISO 8601), how it ended, how long it took, and the files with their sizes.
//! Written when the run starts (status `running`) and again when it stops, each time to a
//! temporary file renamed over the old one; a killed run keeps `running`.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

use hagfish_scenario::LoadedScenario;
use serde::{Deserialize, Serialize};

use crate::CliError;
use crate::utc::iso8601;

/// Name of the manifest in a run directory.
pub const MANIFEST_FILE: &str = "manifest.json";

/// How a run stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Started and not stopped (or killed).
    Running,
    /// The whole duration was simulated.
    Completed,
    /// A step failed; the outputs hold every frame before it.
    Diverged,
    /// Stopped on request (`--stop-after-frames`, SIGINT, SIGTERM); resumable.
    Interrupted,
    /// A tie phase did not tie its knot in its attempts; the outputs hold every frame.
    TieFailed,
}

impl Status {
    /// The name written in the manifest.
    pub fn name(self) -> &'static str {
        match self {
            Status::Running => "running",
            Status::Completed => "completed",
            Status::Diverged => "diverged",
            Status::Interrupted => "interrupted",
            Status::TieFailed => "tie_failed",
        }
    }
}

/// A file of the run directory and its size.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileEntry {
    /// Name inside the run directory.
    pub name: String,
    /// Size (bytes).
    pub bytes: u64,
}

/// The content of `manifest.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Always `hagfish`.
    pub program: String,
    /// The program's version.
    pub version: String,
    /// The scenario file as given on the command line (the resolved copy is `scenario.ron`).
    pub scenario: PathBuf,
    /// The `--set PATH=VALUE` overrides (and `--body FILE` as `body="FILE"`) applied to the
    /// scenario, in order; `scenario.ron` holds their result.
    #[serde(default)]
    pub overrides: Vec<String>,
    /// The scenario's name.
    pub scenario_name: String,
    /// FNV-1a hash of `scenario.ron` (16 hex digits).
    pub scenario_hash: String,
    /// FNV-1a hash of the body file's bytes (16 hex digits): a resume refuses an edited body.
    #[serde(default)]
    pub body_hash: String,
    /// When the run first started.
    pub started_utc: String,
    /// When it last stopped (`null` while running).
    pub ended_utc: Option<String>,
    /// How it stands.
    pub status: Status,
    /// Wall-clock seconds over all its parts (resumes included).
    pub wall_time_s: f64,
    /// Steps taken.
    pub steps: u64,
    /// Frames recorded.
    pub frames: usize,
    /// Simulation time reached (s).
    pub time_s: f64,
    /// FNV-1a hash of the bits of t, q and q̇ at the end (16 hex digits).
    pub final_state_hash: Option<String>,
    /// The error that made the run diverge.
    pub error: Option<String>,
    /// Steps rejected whole by the acceptance bounds and taken as substeps.
    #[serde(default)]
    pub substepped_steps: u64,
    /// The most substeps one step needed (1: none was divided).
    #[serde(default)]
    pub max_substeps: u32,
    /// Steps rejected whole and taken again whole, accepted, with self contacts at the
    /// chain's resolution (`acceptance.resolve_contacts`).
    #[serde(default)]
    pub resolved_contact_steps: u64,
    /// The scenario phase still running when the run stopped (`null`: every phase was
    /// over), e.g. `tie (3_1 not tied, attempt 1 of 2)` when the duration ended first.
    #[serde(default)]
    pub unfinished_phase: Option<String>,
    /// Where each tie phase made its crossover on this body (fraction of the body length
    /// from the head), in phase order: its `at`, or head-ward of it by its `min_tail_d`.
    #[serde(default)]
    pub tie_crossovers_l: Vec<f64>,
    /// Frame counts at which the run was resumed, in order.
    pub resumed_at_frames: Vec<usize>,
    /// Every other file of the run directory with its size, by name.
    pub files: Vec<FileEntry>,
}

impl Manifest {
    /// The manifest of a run of `scenario` with `overrides` starting now.
    pub fn start(scenario: &Path, overrides: Vec<String>, loaded: &LoadedScenario) -> Self {
        Self {
            program: env!("CARGO_PKG_NAME").into(),
            version: env!("CARGO_PKG_VERSION").into(),
            scenario: scenario.to_path_buf(),
            overrides,
            scenario_name: loaded.scenario.name.clone(),
            scenario_hash: loaded.hash(),
            body_hash: loaded.body_hash.clone(),
            started_utc: iso8601(SystemTime::now()),
            ended_utc: None,
            status: Status::Running,
            wall_time_s: 0.0,
            steps: 0,
            frames: 0,
            time_s: 0.0,
            final_state_hash: None,
            error: None,
            substepped_steps: 0,
            max_substeps: 1,
            resolved_contact_steps: 0,
            unfinished_phase: None,
            tie_crossovers_l: Vec::new(),
            resumed_at_frames: Vec::new(),
            files: Vec::new(),
        }
    }

    /// Reads the manifest of the run in `directory`.
    pub fn read(directory: &Path) -> Result<Self, CliError> {
        read_json(directory.join(MANIFEST_FILE))
    }

    /// Lists the files of `directory` and writes the manifest there (atomically).
    pub fn write(&mut self, directory: &Path) -> Result<(), CliError> {
        self.files = list_files(directory)?;
        let path = directory.join(MANIFEST_FILE);
        let fail = |e: std::io::Error| CliError::RunDirectory {
            path: path.clone(),
            reason: e.to_string(),
        };
        let text =
            serde_json::to_string_pretty(self).map_err(|e| fail(std::io::Error::other(e)))?;
        hagfish_run::replace_file(&path, (text + "\n").as_bytes()).map_err(CliError::from)
    }

    /// Marks the end of one part of the run.
    pub fn stop(&mut self, status: Status, wall_time_s: f64) {
        self.status = status;
        self.ended_utc = Some(iso8601(SystemTime::now()));
        self.wall_time_s += wall_time_s;
    }
}

/// The regular files of `directory` except the manifest, temporary and hidden files (the
/// lock), by name.
fn list_files(directory: &Path) -> Result<Vec<FileEntry>, CliError> {
    let fail = |e: std::io::Error| CliError::RunDirectory {
        path: directory.to_path_buf(),
        reason: e.to_string(),
    };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(directory).map_err(fail)? {
        let entry = entry.map_err(fail)?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let metadata = entry.metadata().map_err(fail)?;
        let listed = name != MANIFEST_FILE && !name.ends_with(".partial") && !name.starts_with('.');
        if metadata.is_file() && listed {
            files.push(FileEntry { name, bytes: metadata.len() });
        }
    }
    files.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(files)
}

/// Reads the JSON file at `path` (a run's or a sweep's record; a regular file of at most
/// [`hagfish_anatomy::MAX_DATA_FILE_BYTES`]); a missing, irregular, too large or malformed
/// file is a [`CliError::RunDirectory`].
pub(crate) fn read_json<T: serde::de::DeserializeOwned>(path: PathBuf) -> Result<T, CliError> {
    let bytes = hagfish_anatomy::read_bounded(&path, hagfish_anatomy::MAX_DATA_FILE_BYTES)
        .map_err(|e| CliError::RunDirectory { path: path.clone(), reason: e.to_string() })?;
    serde_json::from_slice(&bytes)
        .map_err(|e| CliError::RunDirectory { path, reason: e.to_string() })
}
