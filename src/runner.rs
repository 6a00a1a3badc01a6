//! Running a scenario into a run directory (`docs/outputs.md`): the whole of `hagfish run`
//! except the command line, so the program, the Python package and sweeps make the same
//! files from the same code.
//!
//! [`run_into_directory`] locks the directory, starts a new run (refusing or replacing one that
//! is there, as asked) or resumes a stopped one from its checkpoint, steps it to its end
//! writing `scenario.ron`, `manifest.json`, the CSV and `.npy` outputs and `checkpoint.ron`
//! as it goes, and records how it ended in the manifest (and the failing state in
//! `diverged.ron`). [`Finished::write_pictures`] then writes the plots, animation, exports
//! and `report.html`.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use hagfish_run::{
    CHECKPOINT_FILE, Checkpoint, Frame, FrameSink, PreparedRun, Progress, Recorder, RunEnd,
    RunError, RunOptions, RunOutcome,
};
use hagfish_scenario::{LoadedScenario, Override};
use hagfish_sim::state_hash;

use crate::CliError;
use crate::manifest::{MANIFEST_FILE, Manifest, Status};
use crate::run_dir::{LockedDirectory, SetAside};

/// The resolved scenario in a run directory.
pub const SCENARIO_FILE: &str = "scenario.ron";

/// The state at which a run diverged.
const DIVERGED_FILE: &str = "diverged.ron";

/// What a run starts from.
#[derive(Clone, Copy, Debug)]
pub enum Source<'a> {
    /// A scenario file with overrides applied in order (`--set`, `--body`).
    Scenario {
        /// The scenario file (RON).
        path: &'a Path,
        /// The overrides.
        overrides: &'a [Override],
    },
    /// The stopped run already in the directory, continued from its checkpoint.
    Stopped,
}

/// What to do with a run the directory already holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Existing {
    /// Refuse to start (the default of `hagfish run`).
    Refuse,
    /// Replace it (`--overwrite`); kept if the new run cannot start.
    Replace,
    /// Continue it from its checkpoint if it is a stopped run of the same scenario; start
    /// afresh if the directory holds none (`--resume`).
    Resume,
}

/// One run to make.
#[derive(Clone, Copy, Debug)]
pub struct RunRequest<'a> {
    /// What it starts from.
    pub source: Source<'a>,
    /// The run directory (created if missing when the source is a scenario).
    pub directory: &'a Path,
    /// What to do with a run already there.
    pub existing: Existing,
    /// Stop after recording the frame with this index (status `interrupted`).
    pub stop_after_frame: Option<usize>,
    /// Allow up to this many steps (default: 10⁸).
    pub max_steps: Option<u64>,
}

/// A run that stopped (completed, interrupted, diverged or failed its tie), with its
/// manifest already written.
#[derive(Debug)]
pub struct Finished {
    /// The scenario as run.
    pub loaded: LoadedScenario,
    /// The run directory.
    pub directory: PathBuf,
    /// How the run ended, its summary and final state.
    pub outcome: RunOutcome,
    /// The manifest as written.
    pub manifest: Manifest,
    /// Wall-clock seconds of this part of the run.
    pub wall_s: f64,
    /// Steps taken by this part (a resumed run counts from its checkpoint).
    pub steps_run: u64,
    _lock: LockedDirectory,
}

/// The body file `path` as an override of the scenario's `body` (made absolute, so that it
/// does not depend on the scenario's directory): how `--body FILE` is applied.
///
/// # Errors
/// [`CliError::RunDirectory`] if the path cannot be made absolute.
pub fn body_override(path: &Path) -> Result<Override, CliError> {
    let absolute = std::path::absolute(path)
        .map_err(|e| CliError::RunDirectory { path: path.to_path_buf(), reason: e.to_string() })?;
    Ok(Override { path: "body".into(), value: format!("\"{}\"", absolute.display()) })
}

/// Runs `request` to its end, calling `progress` after every recorded frame; stops after the
/// step being taken when `stop` becomes true (status `interrupted`, resumable).
///
/// # Errors
/// A [`CliError`] for what stops a run before it starts (bad scenario, body or overrides, a
/// directory in use or holding a run, a run that cannot be resumed) or an output that cannot
/// be written. A run that diverges or fails its tie is not an error here: it is a
/// [`Finished`] whose manifest says so ([`Finished::failure`]).
pub fn run_into_directory(
    request: &RunRequest<'_>,
    stop: &AtomicBool,
    progress: &mut dyn FnMut(&Progress<'_>),
) -> Result<Finished, CliError> {
    let started = Instant::now();
    // Every refusal that does not depend on the directory's run is made before the directory
    // is touched (not even created or locked): scenario, body, overrides, step cap, memory.
    let given = match request.source {
        Source::Scenario { path, overrides } => Some(given_run(path, overrides, request)?),
        Source::Stopped => None,
    };
    let lock = LockedDirectory::lock(request.directory, given.is_some())?;
    // A replacement stopped before its new run's first checkpoint is undone first.
    SetAside::recover(request.directory)?;
    let (loaded, checkpoint, mut manifest, prepared) = open(request, given)?;
    let directory = request.directory.to_path_buf();
    let model = prepared.model();
    let (dofs, joints) = (model.dof_count(), model.body_count());
    let (mut recorder, earlier) =
        prepare(&loaded, &directory, checkpoint.as_ref(), &mut manifest, (dofs, joints))?;
    let options = RunOptions {
        resume: checkpoint.as_ref(),
        stop_after_frame: request.stop_after_frame,
        stop: Some(stop),
        max_steps: request.max_steps,
    };
    let mut sink = Committing { recorder: &mut recorder, earlier };
    let outcome = match prepared.run(&loaded, options, &mut sink, progress) {
        Ok(outcome) => outcome,
        Err(error) => {
            if let Some(earlier) = sink.earlier.take() {
                earlier.restore()?;
            }
            return Err(error.into());
        }
    };
    let wall_s = started.elapsed().as_secs_f64();
    finish(&outcome, &directory, &mut manifest, wall_s)?;
    let steps_run = outcome.summary.steps - checkpoint.as_ref().map_or(0, |c| c.steps);
    Ok(Finished { loaded, directory, outcome, manifest, wall_s, steps_run, _lock: lock })
}

/// A scenario given to run, checked and built before any directory is touched: its world,
/// controller and manifest.
type Given = (LoadedScenario, PreparedRun, Manifest);

/// Loads the scenario at `path` with `overrides`, checks its steps against the request's cap
/// and builds it (the memory check), and starts its manifest.
fn given_run(
    path: &Path,
    overrides: &[Override],
    request: &RunRequest<'_>,
) -> Result<Given, CliError> {
    let loaded = LoadedScenario::load_with(path, overrides)?;
    let prepared = PreparedRun::new(&loaded, request.max_steps)?;
    let given = overrides.iter().map(Override::text).collect();
    let mut manifest = Manifest::start(path, given, &loaded);
    manifest.tie_crossovers_l = loaded.tie_crossovers_l()?;
    Ok((loaded, prepared, manifest))
}

/// The recorder of a new run holding the earlier run's files aside until the new run has
/// its first checkpoint, then discarding them: a kill before that leaves the earlier run
/// recoverable, after it the new run resumable.
struct Committing<'a> {
    recorder: &'a mut Recorder,
    earlier: Option<SetAside>,
}

impl FrameSink for Committing<'_> {
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), RunError> {
        self.recorder.record(frame)
    }

    fn checkpoint(&mut self, checkpoint: &mut Checkpoint) -> Result<(), RunError> {
        self.recorder.checkpoint(checkpoint)?;
        match self.earlier.take() {
            Some(earlier) => earlier.discard().map_err(|e| RunError::Output {
                path: PathBuf::from(".hagfish-previous"),
                source: std::io::Error::other(e.to_string()),
            }),
            None => Ok(()),
        }
    }
}

impl Finished {
    /// Writes the plots, `animation.gif`, the exports and `report.html`, then the manifest
    /// again to list them; returns the seconds it took.
    ///
    /// # Errors
    /// [`CliError::Report`] if the run directory cannot be read or a picture written.
    pub fn write_pictures(&mut self) -> Result<f64, CliError> {
        let written = hagfish_report::write_all(
            &self.directory,
            &hagfish_modes::report_sections(&self.directory),
        )?;
        self.manifest.write(&self.directory)?;
        Ok(written.total_seconds())
    }

    /// The error of a run that diverged or whose tie failed (as `hagfish run` reports it,
    /// exit code 3 or 4), `None` for a completed or interrupted run.
    pub fn failure(&self) -> Option<CliError> {
        let (directory, reason) = (self.directory.clone(), self.manifest.error.clone()?);
        match self.outcome.end {
            RunEnd::TieFailed(_) => Some(CliError::TieFailed { directory, reason }),
            RunEnd::Diverged { .. } => Some(CliError::Diverged { directory, reason }),
            RunEnd::Completed | RunEnd::Interrupted => None,
        }
    }
}

/// What a run or resume starts from.
type Opened = (LoadedScenario, Option<Checkpoint>, Manifest, PreparedRun);

/// The scenario, checkpoint (when resuming), manifest and prepared run of `request`, whose
/// scenario (if it names one) is `given`.
fn open(request: &RunRequest<'_>, given: Option<Given>) -> Result<Opened, CliError> {
    let directory = request.directory;
    let holds_run = directory.join(MANIFEST_FILE).exists();
    match (given, request.existing) {
        (None, _) => {
            let (loaded, checkpoint, manifest) = open_stopped(directory, None)?;
            let prepared = PreparedRun::new(&loaded, request.max_steps)?;
            Ok((loaded, checkpoint, manifest, prepared))
        }
        (Some((given, prepared, _)), Existing::Resume) if holds_run => {
            // Of the same hash, so the same resolved scenario as the one prepared.
            let (loaded, checkpoint, manifest) = open_stopped(directory, Some(&given.hash()))?;
            Ok((loaded, checkpoint, manifest, prepared))
        }
        (Some(_), Existing::Refuse) if holds_run => {
            let status = Manifest::read(directory).map_or("unreadable", |m| m.status.name());
            Err(CliError::RunDirectory {
                path: directory.to_path_buf(),
                reason: format!(
                    "holds a run (status {status}): continue it with --resume, or replace it \
                     with --overwrite"
                ),
            })
        }
        (Some((loaded, prepared, manifest)), _) => Ok((loaded, None, manifest, prepared)),
    }
}

/// Opens the output files (cut to the checkpoint when resuming; new, with `scenario.ron`,
/// otherwise, with an earlier run's files set aside), removes a stale `diverged.ron` and
/// writes the manifest of the starting part.
fn prepare(
    loaded: &LoadedScenario,
    directory: &Path,
    checkpoint: Option<&Checkpoint>,
    manifest: &mut Manifest,
    (dofs, joints): (usize, usize),
) -> Result<(Recorder, Option<SetAside>), CliError> {
    let Some(checkpoint) = checkpoint else {
        // An earlier run here (replaced with --overwrite) is kept until the new one has its
        // first checkpoint, and put back if its files cannot be made.
        let earlier = SetAside::new(directory)?;
        return match start_files(loaded, directory, (dofs, joints), manifest) {
            Ok(recorder) => Ok((recorder, Some(earlier))),
            Err(error) => {
                earlier.restore()?;
                Err(error)
            }
        };
    };
    let recorder = Recorder::reopen(directory, dofs, joints, checkpoint)?;
    manifest.resumed_at_frames.push(checkpoint.frames);
    manifest.status = Status::Running;
    manifest.ended_utc = None;
    manifest.error = None;
    // The failing state of an earlier part of this run no longer describes the directory.
    match std::fs::remove_file(directory.join(DIVERGED_FILE)) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            return Err(CliError::RunDirectory {
                path: directory.join(DIVERGED_FILE),
                reason: e.to_string(),
            });
        }
        _ => {}
    }
    manifest.write(directory)?;
    Ok((recorder, None))
}

/// The files a new run starts with in `directory`: the recorder's outputs, `scenario.ron`
/// and the manifest.
fn start_files(
    loaded: &LoadedScenario,
    directory: &Path,
    (dofs, joints): (usize, usize),
    manifest: &mut Manifest,
) -> Result<Recorder, CliError> {
    let recorder = Recorder::create(directory, dofs, joints)?;
    hagfish_run::replace_file(&directory.join(SCENARIO_FILE), loaded.resolved_text().as_bytes())?;
    manifest.write(directory)?;
    Ok(recorder)
}

/// The scenario, checkpoint and manifest of the stopped run in `directory`, which must be of
/// the scenario with hash `expected` if one is given.
fn open_stopped(
    directory: &Path,
    expected: Option<&str>,
) -> Result<(LoadedScenario, Option<Checkpoint>, Manifest), CliError> {
    let manifest = Manifest::read(directory)?;
    if manifest.status == Status::Completed {
        return Err(CliError::RunDirectory {
            path: directory.to_path_buf(),
            reason: "the run is completed: nothing to resume".into(),
        });
    }
    let loaded = LoadedScenario::load(directory.join(SCENARIO_FILE))?;
    let path = directory.join(CHECKPOINT_FILE);
    let checkpoint = Checkpoint::read(&path)?;
    if checkpoint.body_hash != loaded.body_hash {
        return Err(CliError::RunDirectory {
            path: loaded.scenario.body.clone(),
            reason: format!(
                "the body file changed since the run's checkpoint (hash {} then, {} now): \
                 resuming would continue another body; start a new run",
                checkpoint.body_hash, loaded.body_hash
            ),
        });
    }
    if let Some(then) = checkpoint.referenced_files_hash.as_ref()
        && *then != loaded.referenced_files_hash
    {
        return Err(CliError::RunDirectory {
            path: directory.join(SCENARIO_FILE),
            reason: format!(
                "a knot plan, modal basis or replay file the scenario reads changed since the \
                 run's checkpoint (hash {then:?} then, {:?} now): resuming would continue \
                 another run; start a new run",
                loaded.referenced_files_hash
            ),
        });
    }
    let hash = loaded.hash();
    let hashes = [Some(checkpoint.scenario_hash.as_str()), Some(&manifest.scenario_hash), expected];
    if let Some(other) = hashes.into_iter().flatten().find(|h| *h != hash) {
        return Err(CliError::RunDirectory {
            path,
            reason: format!(
                "the run is of another scenario: hash {other} (checkpoint, manifest or the \
                 scenario given) differs from {hash} of {SCENARIO_FILE}"
            ),
        });
    }
    Ok((loaded, Some(checkpoint), manifest))
}

/// Writes the end of the run into the manifest (and `diverged.ron` for a diverged run).
fn finish(
    outcome: &RunOutcome,
    directory: &Path,
    manifest: &mut Manifest,
    wall: f64,
) -> Result<(), CliError> {
    let (status, error) = match &outcome.end {
        RunEnd::Completed => (Status::Completed, None),
        RunEnd::Interrupted => (Status::Interrupted, None),
        RunEnd::Diverged { error, at } => {
            at.write(&directory.join(DIVERGED_FILE))?;
            (Status::Diverged, Some(error.to_string()))
        }
        RunEnd::TieFailed(failure) => {
            (Status::TieFailed, Some(RunError::TieFailed(failure.clone()).to_string()))
        }
    };
    manifest.stop(status, wall);
    manifest.steps = outcome.summary.steps;
    manifest.frames = outcome.summary.frames;
    manifest.time_s = outcome.state.t;
    manifest.substepped_steps = outcome.summary.substepped_steps;
    manifest.max_substeps = outcome.summary.max_substeps;
    manifest.resolved_contact_steps = outcome.summary.resolved_steps;
    manifest.unfinished_phase.clone_from(&outcome.summary.unfinished_phase);
    manifest.final_state_hash = Some(state_hash(&outcome.state));
    manifest.error = error;
    manifest.write(directory)
}
