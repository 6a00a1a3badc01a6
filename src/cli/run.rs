//! `hagfish run SCENARIO --out DIR`: runs a scenario and writes its run directory as it goes
//! (`docs/outputs.md`): `scenario.ron` (resolved), `manifest.json`, the CSV and `.npy` outputs
//! and `checkpoint.ron` after every frame. `hagfish run --resume DIR` continues a stopped run
//! from its checkpoint, bit for bit.

use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use clap::Args;
use hagfish_control::Phase;
use hagfish_scenario::Override;
use hagfish_sim::DynamicsBackend;

use super::progress::Reporter;
use crate::CliError;
use crate::manifest::Status;
use crate::runner::{Existing, Finished, RunRequest, Source, body_override, run_into_directory};

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
    /// seconds=10`); VALUE as in the scenario files (`Trefoil(Left)`, `(0.0, 2.0)`,
    /// `Some((linear_dyn_s_per_cm3: 0.0, quadratic_g_per_cm3: 1.0))`). Recorded in the run's
    /// scenario.ron and manifest.json.
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
/// (exit code 130): while stepping it stops at the next stage boundary of the step being taken
/// (abandoning that step: `hagfish_sim::StopRequest`), resumable from its last frame; while
/// the pictures and report are written it exits at once (the run itself is complete and
/// recorded; `hagfish render` and `hagfish report` write them again).
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let overrides = overrides(args)?;
    let (source, directory, existing) = match (&args.resume, &args.scenario, &args.out) {
        (Some(Some(_)), None, None) if !overrides.is_empty() => {
            return Err(CliError::Usage(
                "--set and --body change a scenario: give them with SCENARIO --out DIR, not \
                 with --resume DIR (which continues the run as it was started)",
            ));
        }
        (Some(Some(directory)), None, None) => (Source::Stopped, directory, Existing::Resume),
        (resume @ (Some(None) | None), Some(path), Some(directory)) => {
            let existing = match (resume, args.overwrite) {
                (Some(None), _) => Existing::Resume,
                (_, true) => Existing::Replace,
                _ => Existing::Refuse,
            };
            (Source::Scenario { path, overrides: &overrides }, directory, existing)
        }
        _ => return Err(CliError::Usage(USAGE)),
    };
    let request = RunRequest {
        source,
        directory,
        existing,
        stop_after_frame: args.stop_after_frames,
        max_steps: args.max_steps,
    };

    let signalled = Arc::new(AtomicBool::new(false));
    let reporting = Arc::new(AtomicBool::new(false));
    let (flag, in_report) = (Arc::clone(&signalled), Arc::clone(&reporting));
    let _stop_signal = super::stop_signal::on_stop_signal(move || {
        if in_report.load(Ordering::Relaxed) {
            eprintln!(
                "interrupted while writing the pictures and report (the run is recorded; \
                 `hagfish render DIR` and `hagfish report DIR` write them again)"
            );
            std::process::exit(130);
        }
        flag.store(true, Ordering::Relaxed);
    })?;
    let mut reporter: Option<Reporter> = None;
    let quiet = args.quiet;
    let mut finished = run_into_directory(&request, &signalled, &mut |p| {
        reporter.get_or_insert_with(|| Reporter::new(quiet, p.duration)).update(p);
    })?;
    if let Some(reporter) = reporter {
        reporter.finish();
    }
    summarise(&finished, out)?;
    reporting.store(true, Ordering::Relaxed);
    let frames = finished.outcome.summary.frames;
    if signalled.load(Ordering::Relaxed) {
        return Err(CliError::Interrupted { directory: directory.clone(), frames });
    }
    let seconds = finished.write_pictures()?;
    writeln!(out, "pictures, report and exports in {seconds:.2} s")?;
    // A signal from here on ends the process in the handler above.
    finished.failure().map_or(Ok(()), Err)
}

/// How `hagfish run` is called.
const USAGE: &str = "give SCENARIO --out DIR [--resume | --overwrite], or --resume DIR alone";

/// The overrides of `--set` in order, then `--body` as an override of `body`.
fn overrides(args: &RunArgs) -> Result<Vec<Override>, CliError> {
    let mut overrides =
        args.set.iter().map(|text| Override::parse(text)).collect::<Result<Vec<_>, _>>()?;
    if let Some(body) = &args.body {
        overrides.push(body_override(body)?);
    }
    Ok(overrides)
}

/// The summary on stdout.
fn summarise(finished: &Finished, out: &mut dyn Write) -> Result<(), CliError> {
    let Finished { loaded, directory, outcome, manifest, wall_s: wall, steps_run, .. } = finished;
    let (status, summary) = (manifest.status, &outcome.summary);
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
    let steps = (*steps_run).max(1) as f64;
    let stages: Vec<String> = summary
        .timings
        .stages()
        .iter()
        .map(|(name, seconds)| format!("{name} {:.1}", 1e6 * seconds / steps))
        .collect();
    if let Some(phase) = summary.unfinished_phase.as_ref().filter(|_| status == Status::Completed) {
        writeln!(out, "the duration ended in phase {phase}: a longer duration_s lets it finish")?;
    }
    let ties = loaded.scenario.phases.iter().filter_map(|p| match p {
        Phase::Tie(tie) => Some(tie),
        _ => None,
    });
    for (tie, &at) in ties.zip(&manifest.tie_crossovers_l) {
        if let Some(diameters) = tie.min_tail_d.filter(|_| at != tie.at) {
            let decimals = (3..12).find(|&d| format!("{at:.d$}") != format!("{:.d$}", tie.at));
            let decimals = decimals.unwrap_or(12);
            writeln!(
                out,
                "tie crossover at {at:.decimals$} L, not {} L: on this body {} L leaves less \
                 than min_tail_d = {diameters} local diameters tail-ward",
                tie.at, tie.at,
            )?;
        }
    }
    if summary.resolved_steps > 0 {
        writeln!(
            out,
            "steps rejected whole (acceptance bounds) and taken whole again with self contacts \
             every {:.1} bodies: {}",
            summary.resolved_cluster_bodies, summary.resolved_steps
        )?;
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
    let bodies = loaded.body.body_count();
    if loaded.scenario.backend == DynamicsBackend::DenseReduced && bodies >= DENSE_HINT_BODIES {
        writeln!(
            out,
            "{bodies} bodies on the dense backend, whose step grows with the cube of the \
             bodies: `--set backend=SparseMaximal` grows linearly (docs/performance.md, \
             \"Scaling with the number of bodies\")"
        )?;
    }
    Ok(())
}

/// From this many bodies on, a run on the dense backend names the sparse one in its summary:
/// at 200 bodies the sparse step without rows is ≈ 8× faster, at 1000 ≈ 90×
/// (docs/performance.md), where the dense one's O(n³) factor starts to dominate a run.
const DENSE_HINT_BODIES: usize = 200;
