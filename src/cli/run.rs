//! `hagfish run SCENARIO --out DIR`: runs a scenario and writes its run directory as it goes
//! (`docs/outputs.md`): `scenario.ron` (resolved), `manifest.json`, the CSV and `.npy` outputs
//! and `checkpoint.ron` after every frame. `hagfish run --resume DIR` continues a stopped run
//! from its checkpoint, bit for bit.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use clap::Args;
use hagfish_sim::{
    CHECKPOINT_FILE, Checkpoint, LoadedScenario, Override, Recorder, RunEnd, RunOptions,
    RunOutcome, SimError, state_hash,
};

use super::CliError;
use super::manifest::{MANIFEST_FILE, Manifest, Status};
use super::progress::Reporter;
use super::run_dir::{LockedDirectory, SetAside};

/// The resolved scenario in a run directory.
const SCENARIO_FILE: &str = "scenario.ron";

/// The state at which a run diverged.
const DIVERGED_FILE: &str = "diverged.ron";

/// Arguments of `hagfish run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scenario file (RON), e.g. data/scenarios/form.ron.
    scenario: Option<PathBuf>,
    /// Output directory (created if missing; its outputs are replaced unless --resume).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Continue the stopped (interrupted, killed or diverged) run in DIR from its checkpoint:
    /// `--resume DIR`, or `SCENARIO --out DIR --resume`, which checks that DIR holds a run of
    /// SCENARIO and starts one if DIR has none yet (for job scripts that are simply rerun).
    #[arg(long, value_name = "DIR", num_args = 0..=1)]
    resume: Option<Option<PathBuf>>,
    /// Override a scenario value for this run: `--set PATH=VALUE`, repeatable, with the dotted
    /// paths of `hagfish params` (e.g. `--set time_step_s=0.02`,
    /// `--set Thigmotaxis.parameters.tail_pull_dyn=0`, `--set phases[2].Thigmotaxis.until.
    /// seconds=10`). Recorded in the run's scenario.ron and manifest.json.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    set: Vec<String>,
    /// Replace the run already in DIR (its files only; the old run is kept if the new one
    /// cannot start). Without it, a DIR that holds a run is refused.
    #[arg(long, conflicts_with = "resume")]
    overwrite: bool,
    /// Use this biometrics (or rod) file instead of the scenario's `body`.
    #[arg(long, value_name = "FILE")]
    body: Option<PathBuf>,
    /// No progress on stderr; only the final summary on stdout.
    #[arg(long)]
    quiet: bool,
    /// Stop after recording the frame with this index and leave a resumable run (status
    /// `interrupted`); for tests and for cluster time limits.
    #[arg(long, value_name = "K")]
    stop_after_frames: Option<usize>,
    /// Allow a run of up to N steps (duration / time step); without it a scenario needing more
    /// than 10⁸ steps is refused before it starts (it would run for hours and fill the disk).
    #[arg(long, value_name = "N")]
    max_steps: Option<u64>,
}

/// Runs or resumes, then prints the summary. A diverged run is an error (exit code 3) after
/// its outputs, checkpoint and manifest are written; so is a run stopped by SIGINT or SIGTERM
/// (exit code 130): while stepping it stops after the step being taken, resumable from its
/// last frame; while the pictures and report are written it exits at once (the run itself is
/// complete and recorded; `hagfish render` and `hagfish report` write them again).
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let started = Instant::now();
    let _lock = match (&args.resume, &args.out) {
        (Some(Some(directory)), None) => LockedDirectory::lock(directory, false)?,
        (_, Some(directory)) => LockedDirectory::lock(directory, true)?,
        _ => return Err(CliError::Usage(USAGE)),
    };
    let (loaded, directory, checkpoint, mut manifest) = open(args)?;
    let mut recorder = prepare(&loaded, &directory, checkpoint.as_ref(), &mut manifest)?;

    let signalled = Arc::new(AtomicBool::new(false));
    let reporting = Arc::new(AtomicBool::new(false));
    let (flag, in_report) = (Arc::clone(&signalled), Arc::clone(&reporting));
    ctrlc::set_handler(move || {
        if in_report.load(Ordering::Relaxed) {
            eprintln!(
                "interrupted while writing the pictures and report (the run is recorded; \
                 `hagfish render DIR` and `hagfish report DIR` write them again)"
            );
            std::process::exit(130);
        }
        flag.store(true, Ordering::Relaxed);
    })?;
    let mut reporter = Reporter::new(args.quiet, loaded.scenario.duration_s);
    let options = RunOptions {
        resume: checkpoint.as_ref(),
        stop_after_frame: args.stop_after_frames,
        stop: Some(&signalled),
        max_steps: args.max_steps,
    };
    let outcome = hagfish_sim::run(&loaded, options, &mut recorder, &mut |p| reporter.update(p))?;
    reporter.finish();
    let wall = started.elapsed().as_secs_f64();
    let diverged = finish(&outcome, &directory, &mut manifest, wall)?;
    let steps_run = outcome.summary.steps - checkpoint.as_ref().map_or(0, |c| c.steps);
    summarise(&loaded, &directory, &outcome, manifest.status, wall, steps_run, out)?;
    reporting.store(true, Ordering::Relaxed);
    if signalled.load(Ordering::Relaxed) {
        return Err(CliError::Interrupted { directory, frames: outcome.summary.frames });
    }
    let written = hagfish_report::write_all(&directory)?;
    writeln!(out, "pictures, report and exports in {:.2} s", written.total_seconds())?;
    manifest.write(&directory)?; // again, to list the pictures and the report too
    match (diverged, &outcome.end) {
        (Some(reason), RunEnd::TieFailed(_)) => Err(CliError::TieFailed { directory, reason }),
        (Some(reason), _) => Err(CliError::Diverged { directory, reason }),
        (None, RunEnd::Interrupted) if signalled.load(Ordering::Relaxed) => {
            Err(CliError::Interrupted { directory, frames: outcome.summary.frames })
        }
        (None, _) => Ok(()),
    }
}

/// What a run or resume starts from.
type Opened = (LoadedScenario, PathBuf, Option<Checkpoint>, Manifest);

/// The scenario, run directory, checkpoint (when resuming) and manifest the arguments name.
fn open(args: &RunArgs) -> Result<Opened, CliError> {
    let overrides = overrides(args)?;
    match (&args.resume, &args.scenario, &args.out) {
        (Some(Some(directory)), None, None) if overrides.is_empty() => {
            open_stopped(directory, None)
        }
        (Some(Some(_)), None, None) => Err(CliError::Usage(
            "--set and --body change a scenario: give them with SCENARIO --out DIR, not with \
             --resume DIR (which continues the run as it was started)",
        )),
        (Some(None), Some(scenario), Some(directory)) if directory.join(MANIFEST_FILE).exists() => {
            let hash = LoadedScenario::load_with(scenario, &overrides)?.hash();
            open_stopped(directory, Some(&hash))
        }
        (None, Some(_), Some(directory))
            if directory.join(MANIFEST_FILE).exists() && !args.overwrite =>
        {
            let status = Manifest::read(directory).map_or("unreadable", |m| m.status.name());
            Err(CliError::RunDirectory {
                path: directory.clone(),
                reason: format!(
                    "holds a run (status {status}): continue it with --resume, or replace it \
                     with --overwrite"
                ),
            })
        }
        (Some(None) | None, Some(scenario), Some(directory)) => {
            let loaded = LoadedScenario::load_with(scenario, &overrides)?;
            let given = overrides.iter().map(Override::text).collect();
            let manifest = Manifest::start(scenario, given, &loaded);
            Ok((loaded, directory.clone(), None, manifest))
        }
        _ => Err(CliError::Usage(USAGE)),
    }
}

/// How `hagfish run` is called.
const USAGE: &str = "give SCENARIO --out DIR [--resume | --overwrite], or --resume DIR alone";

/// The overrides of `--set` in order, then `--body` as an override of `body` (made absolute,
/// so that it does not depend on the scenario's directory).
fn overrides(args: &RunArgs) -> Result<Vec<Override>, CliError> {
    let mut overrides =
        args.set.iter().map(|text| Override::parse(text)).collect::<Result<Vec<_>, _>>()?;
    if let Some(body) = &args.body {
        let absolute = std::path::absolute(body)
            .map_err(|e| CliError::RunDirectory { path: body.clone(), reason: e.to_string() })?;
        overrides
            .push(Override { path: "body".into(), value: format!("\"{}\"", absolute.display()) });
    }
    Ok(overrides)
}

/// Opens the output files (cut to the checkpoint when resuming; new, with `scenario.ron`,
/// otherwise), removes a stale `diverged.ron` and writes the manifest of the starting part.
fn prepare(
    loaded: &LoadedScenario,
    directory: &Path,
    checkpoint: Option<&Checkpoint>,
    manifest: &mut Manifest,
) -> Result<Recorder, CliError> {
    let model = loaded.body.to_model()?;
    let (dofs, joints) = (model.dof_count(), model.body_count());
    let recorder = match checkpoint {
        Some(checkpoint) => Recorder::reopen(directory, dofs, joints, checkpoint)?,
        None => {
            // An earlier run here (replaced with --overwrite) is kept until the new one has
            // its files, and put back if they cannot be made.
            let earlier = SetAside::new(directory)?;
            match start_files(loaded, directory, (dofs, joints), manifest) {
                Ok(recorder) => {
                    earlier.discard()?;
                    recorder
                }
                Err(error) => {
                    earlier.restore()?;
                    return Err(error);
                }
            }
        }
    };
    if let Some(checkpoint) = checkpoint {
        manifest.resumed_at_frames.push(checkpoint.frames);
        manifest.status = Status::Running;
        manifest.ended_utc = None;
        manifest.error = None;
    }
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
    Ok(recorder)
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
    hagfish_sim::replace_file(&directory.join(SCENARIO_FILE), loaded.resolved_text().as_bytes())?;
    manifest.write(directory)?;
    Ok(recorder)
}

/// The scenario, checkpoint and manifest of the stopped run in `directory`, which must be of
/// the scenario with hash `expected` if one is given.
fn open_stopped(directory: &Path, expected: Option<&str>) -> Result<Opened, CliError> {
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
    Ok((loaded, directory.to_path_buf(), Some(checkpoint), manifest))
}

/// Writes the end of the run into the manifest (and `diverged.ron` for a diverged run);
/// returns the error of a diverged run or a failed tie phase.
fn finish(
    outcome: &RunOutcome,
    directory: &Path,
    manifest: &mut Manifest,
    wall: f64,
) -> Result<Option<String>, CliError> {
    let (status, error) = match &outcome.end {
        RunEnd::Completed => (Status::Completed, None),
        RunEnd::Interrupted => (Status::Interrupted, None),
        RunEnd::Diverged { error, at } => {
            at.write(&directory.join(DIVERGED_FILE))?;
            (Status::Diverged, Some(error.to_string()))
        }
        RunEnd::TieFailed(failure) => {
            (Status::TieFailed, Some(SimError::TieFailed(*failure).to_string()))
        }
    };
    manifest.stop(status, wall);
    manifest.steps = outcome.summary.steps;
    manifest.frames = outcome.summary.frames;
    manifest.time_s = outcome.state.t;
    manifest.substepped_steps = outcome.summary.substepped_steps;
    manifest.max_substeps = outcome.summary.max_substeps;
    manifest.unfinished_phase.clone_from(&outcome.summary.unfinished_phase);
    manifest.final_state_hash = Some(state_hash(&outcome.state));
    manifest.error.clone_from(&error);
    manifest.write(directory)?;
    Ok(error)
}

/// The summary on stdout.
fn summarise(
    loaded: &LoadedScenario,
    directory: &Path,
    outcome: &RunOutcome,
    status: Status,
    wall: f64,
    steps_run: u64,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let summary = &outcome.summary;
    let last = summary.knots.last().and_then(|k| k.knot.as_ref());
    writeln!(
        out,
        "scenario {} → {}  ({})\nsteps {}  frames {}  t = {:.2} s  wall time {:.2} s\nfinal knot {}  max self penetration {:.2} % of the local radius  max wall penetration {:.4} cm  max limit excess {:.3}°",
        loaded.scenario.name,
        directory.display(),
        status.name(),
        summary.steps,
        summary.frames,
        outcome.state.t,
        wall,
        last.map_or("?".to_string(), |k| format!("{} (agreement {:.2})", k.knot, k.agreement)),
        100.0 * summary.maxima.self_penetration_relative,
        summary.maxima.wall_penetration,
        summary.maxima.limit_excess.to_degrees(),
    )?;
    for phase in summary.force_field.phases() {
        let Some(stats) = summary.force_field.stats(phase).filter(|s| s.mean_dyn_cm > 0.0) else {
            continue;
        };
        writeln!(
            out,
            "thigmotaxic force field in {phase}: mean |f| {:.0} → {:.0} dyn·cm (first → last quarter), \
             zero tail-ward of the knot in {:.1} % of samples, roughness in space {:.2}, in time {:.2}",
            stats.first_quarter_mean_dyn_cm,
            stats.last_quarter_mean_dyn_cm,
            100.0 * stats.tailward_zero_fraction,
            stats.spatial_roughness,
            stats.temporal_roughness,
        )?;
    }
    let steps = steps_run.max(1) as f64;
    let stages: Vec<String> = summary
        .timings
        .stages()
        .iter()
        .map(|(name, seconds)| format!("{name} {:.1}", 1e6 * seconds / steps))
        .collect();
    if let Some(phase) = summary.unfinished_phase.as_ref().filter(|_| status == Status::Completed) {
        writeln!(out, "the duration ended in phase {phase}: a longer duration_s lets it finish")?;
    }
    if summary.substepped_steps > 0 {
        writeln!(
            out,
            "steps rejected whole (acceptance bounds) and taken as substeps: {}, up to {} per step",
            summary.substepped_steps, summary.max_substeps
        )?;
    }
    writeln!(
        out,
        "mean µs per step: {}  (total {:.1})",
        stages.join(", "),
        1e6 * summary.timings.total() / steps
    )?;
    Ok(())
}
