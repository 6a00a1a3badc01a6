//! `hagfish run SCENARIO --out DIR`: runs a scenario and writes its outputs as it goes.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use hagfish_sim::{LoadedScenario, Progress, Recorder};

use super::CliError;

/// Arguments of `hagfish run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scenario file (RON), e.g. data/scenarios/form.ron.
    scenario: PathBuf,
    /// Output directory (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Print only the final summary.
    #[arg(long)]
    quiet: bool,
}

/// Runs the scenario, printing one progress line per simulated second unless `--quiet`.
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let loaded = LoadedScenario::load(&args.scenario)?;
    let started = std::time::Instant::now();
    let mut last_second = -1.0;
    let mut report = |p: &Progress<'_>| {
        if args.quiet || p.time.floor() <= last_second {
            return;
        }
        last_second = p.time.floor();
        let knot = p.knot.map_or("?".to_string(), |k| format!("{} ({:.2})", k.knot, k.agreement));
        // Progress lines go to stderr so stdout stays the summary.
        let _ = writeln!(
            std::io::stderr(),
            "t = {:6.2} / {:.2} s  phase {:5}  knot {knot}",
            p.time,
            p.duration,
            p.phase
        );
    };
    let mut recorder = Recorder::create(&args.out)?;
    let summary = hagfish_sim::run(&loaded, &mut recorder, &mut report)?;
    let last = summary.knots.last().and_then(|k| k.knot.as_ref());
    writeln!(
        out,
        "scenario {} → {}\nsteps {}  frames {}  wall time {:.2} s\nfinal knot {}  max self penetration {:.2} % of the local radius  max wall penetration {:.4} cm  max limit excess {:.3}°",
        loaded.scenario.name,
        args.out.display(),
        summary.steps,
        summary.frames,
        started.elapsed().as_secs_f64(),
        last.map_or("?".to_string(), |k| format!("{} (agreement {:.2})", k.knot, k.agreement)),
        100.0 * summary.maxima.self_penetration_relative,
        summary.maxima.wall_penetration,
        summary.maxima.limit_excess.to_degrees(),
    )?;
    let steps = summary.steps.max(1) as f64;
    let stages: Vec<String> = summary
        .timings
        .stages()
        .iter()
        .map(|(name, seconds)| format!("{name} {:.1}", 1e6 * seconds / steps))
        .collect();
    writeln!(
        out,
        "mean µs per step: {}  (total {:.1})",
        stages.join(", "),
        1e6 * summary.timings.total() / steps
    )?;
    let written = hagfish_report::write_all(&args.out)?;
    writeln!(out, "pictures, report and exports in {:.2} s", written.total_seconds())?;
    Ok(())
}
