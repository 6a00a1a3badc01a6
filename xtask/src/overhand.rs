//! `cargo xtask overhand`: Choi, Tong, Jawed & Joo 2021's knot-tying case
//! (`hagfish_validation::overhand_pull`): the overhand knots with n turns pulled tight at each
//! end speed, one run per (n, u), `jobs` at a time. Prints, as Markdown, a row per run (how it
//! ended, the largest force drop, the deepest penetration, the wall time), per knot the
//! smoothed force at the same end-to-end distances for every speed, and per knot the speeds'
//! spread along the whole pull; writes each run's samples to `<out>/n<N>_u<U>.csv` when `out`
//! is given. Each pull's steps, wall time and last force go to stderr as it ends.

use std::fmt::Write as _;
use std::path::Path;

use hagfish_scenario::Override;
use hagfish_validation::ValidationError;
use hagfish_validation::overhand_pull::{self, PullEnd, PulledKnot, relative_spread, spread_along};

use crate::family::{comma_list, in_parallel, shell_word};

/// The smoothed curve's spacing (cm of end-to-end distance).
const SPACING_CM: f64 = 0.25;

/// The window of the loop's largest turn (s): a snap takes a fraction of it, the loop's drift
/// as the knot closes turns it by a degree or less.
const LOOP_TURN_WINDOW_S: f64 = 0.1;

/// The forces at which the speeds are compared (dyn), each at the end-to-end distance where
/// the first speed's smoothed force first reaches it.
const COMPARED_DYN: [f64; 4] = [50.0, 100.0, 200.0, 300.0];

/// What to run.
pub struct Request<'a> {
    /// Turns n.
    pub turns: &'a [usize],
    /// Speeds of each end u (cm/s).
    pub speeds: &'a [f64],
    /// Time step (s).
    pub time_step: f64,
    /// The force that ends a pull (dyn).
    pub stop_force: f64,
    /// The force (dyn) from which the largest fall of the force is looked for: the start of
    /// the pull, where the knot's starting curve takes up its slack, is left out.
    pub drop_from: f64,
    /// The forces (dyn) from which the speeds' spread along the pull is counted, one row each
    /// (the first speed's force reaching it), e.g. 300 for the tight knot alone.
    pub spread_from: &'a [f64],
    /// Runs at a time.
    pub jobs: usize,
    /// Where to write the samples, if anywhere.
    pub out: Option<&'a Path>,
    /// `--set PATH=VALUE` overrides of `data/validation/overhand_pull.ron` for every run.
    pub sets: &'a [String],
}

/// Runs the grid and prints its tables.
pub fn run(root: &Path, request: &Request<'_>) -> Result<(), String> {
    let cases: Vec<(usize, f64)> =
        request.turns.iter().flat_map(|&n| request.speeds.iter().map(move |&u| (n, u))).collect();
    let sets: Vec<Override> = request
        .sets
        .iter()
        .map(|s| Override::parse(s).map_err(|e| format!("--set {s}: {e}")))
        .collect::<Result<_, _>>()?;
    let runs = in_parallel(&cases, request.jobs, |&case| {
        let run = overhand_pull::run(root, case, request.time_step, request.stop_force, &sets);
        eprintln!("{}", progress(case, &run));
        run
    })?;
    let runs: Vec<PulledKnot> =
        runs.into_iter().collect::<Result<_, _>>().map_err(|e| e.to_string())?;
    if let Some(out) = request.out {
        write_samples(out, &runs)?;
    }
    println!("{}", run_table(&runs, request.drop_from));
    println!("{}", speed_table(&runs));
    println!("{}", curve_spread_table(&runs, request.spread_from));
    println!(
        "`cargo xtask overhand --turns {} --speeds {} --time-step {} --stop-force {} \
         --drop-from {} --spread-from {}{}`; data/validation/overhand_pull.ron (μ = 0.1 unless set)",
        comma_list(request.turns),
        comma_list(request.speeds),
        request.time_step,
        request.stop_force,
        request.drop_from,
        comma_list(request.spread_from),
        request.sets.iter().map(|s| format!(" --set {}", shell_word(s))).collect::<String>(),
    );
    Ok(())
}

/// The line printed to stderr as each pull of `(turns, speed)` ends, so that a long grid
/// shows its progress.
fn progress((turns, speed): (usize, f64), run: &Result<PulledKnot, ValidationError>) -> String {
    let case = format!("overhand: n = {turns}, u = {speed} cm/s");
    match run {
        Ok(run) => format!(
            "{case}: {} steps ({} retried) in {:.1} s, last force {}",
            run.steps,
            run.retried_steps,
            run.wall_s,
            run.samples.last().map_or("—".into(), |s| format!("{:.1} dyn", s.force_dyn)),
        ),
        Err(error) => format!("{case}: failed: {error}"),
    }
}

/// A row per run, its largest fall of the force counted from `drop_from` dyn.
fn run_table(runs: &[PulledKnot], drop_from: f64) -> String {
    let mut table = String::from(
        "| n | u (cm/s) | knot at start → end | ended | end-to-end (cm) | force (dyn) | largest drop | \
         largest turn of the loop in 0.1 s | deepest penetration (% h) | grip off its target (largest, cm) | \
         steps (retried) | wall (s) | ms/step |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for run in runs {
        let last = run.samples.last();
        let ended = match &run.end {
            PullEnd::Force => "at the force".to_string(),
            PullEnd::Distance => "at the distance".to_string(),
            PullEnd::Failed(why) => format!("failed: {why}"),
        };
        let drop = run.largest_drop(SPACING_CM, drop_from).map_or("—".into(), |d| {
            format!("{:.0} % from {:.0} dyn at {:.1} cm", 100.0 * d.fraction, d.from_dyn, d.from_cm)
        });
        let turn = run.largest_loop_turn(LOOP_TURN_WINDOW_S).map_or("—".into(), |turn| {
            format!("{:.1}° at {:.1} cm", turn.angle_rad.to_degrees(), turn.at_cm)
        });
        let grip = run
            .largest_grip_error()
            .map_or("—".into(), |g| format!("{:.1e} at {:.1} cm", g.error_cm, g.at_cm));
        let _ = writeln!(
            table,
            "| {} | {} | {} → {} | {ended} | {:.2} | {:.1} | {drop} | {turn} | {:.3} | {grip} | {} ({}) | {:.1} | {:.2} |",
            run.turns,
            run.end_speed_cm_per_s,
            run.knots.0,
            run.knots.1,
            last.map_or(f64::NAN, |s| s.end_to_end_cm),
            last.map_or(f64::NAN, |s| s.force_dyn),
            100.0 * run.max_penetration_relative,
            run.steps,
            run.retried_steps,
            run.wall_s,
            1e3 * run.wall_s / run.steps as f64,
        );
    }
    table
}

/// The runs grouped by knot (turns n), in the order the knots first appear.
fn by_knot(runs: &[PulledKnot]) -> Vec<(usize, Vec<&PulledKnot>)> {
    let mut turns: Vec<usize> = runs.iter().map(|r| r.turns).collect();
    turns.dedup();
    turns.into_iter().map(|n| (n, runs.iter().filter(|r| r.turns == n).collect())).collect()
}

/// Per knot, the smoothed force of every speed at the distances where the first speed's
/// reaches [`COMPARED_DYN`], and the largest spread over the mean.
fn speed_table(runs: &[PulledKnot]) -> String {
    let mut table = String::from(
        "| n | end-to-end (cm) | force at each speed (dyn) | spread (max − min)/mean |\n|---|---|---|---|\n",
    );
    for (n, same) in by_knot(runs) {
        let Some(first) = same.first() else { continue };
        let curve = first.smoothed_curve(SPACING_CM);
        for target in COMPARED_DYN {
            let Some(&(at, _)) = curve.iter().find(|&&(_, f)| f >= target) else { continue };
            let forces: Option<Vec<f64>> = same.iter().map(|r| r.smoothed_force(at)).collect();
            let Some(forces) = forces else { continue };
            let listed: Vec<String> = same
                .iter()
                .zip(&forces)
                .map(|(r, f)| format!("{:.1} ({} cm/s)", f, r.end_speed_cm_per_s))
                .collect();
            let _ = writeln!(
                table,
                "| {n} | {at:.2} | {} | {:.3} |",
                listed.join(", "),
                relative_spread(&forces)
            );
        }
    }
    table
}

/// Per knot and per force of `spread_from`, the spread of the speeds' smoothed forces along the
/// pull from where the first speed's force reaches it to the end ([`spread_along`], every
/// [`SPACING_CM`]): how many distances, the median, the 90th percentile and the largest.
fn curve_spread_table(runs: &[PulledKnot], spread_from: &[f64]) -> String {
    let mut table = String::from(
        "| n | from (dyn) | distances compared | median spread | 90th percentile | largest |\n\
         |---|---|---|---|---|---|\n",
    );
    let knots = by_knot(runs);
    for ((n, same), &from) in knots.iter().flat_map(|k| spread_from.iter().map(move |f| (k, f))) {
        let mut spreads = spread_along(same, SPACING_CM, from);
        if spreads.is_empty() {
            continue;
        }
        spreads.sort_by(f64::total_cmp);
        let at = |q: f64| spreads[((q * spreads.len() as f64) as usize).min(spreads.len() - 1)];
        let _ = writeln!(
            table,
            "| {n} | {from} | {} | {:.3} | {:.3} | {:.3} |",
            spreads.len(),
            at(0.5),
            at(0.9),
            at(1.0),
        );
    }
    table
}

/// Each run's samples as `n<N>_u<U>.csv`: time since the pull started, end-to-end distance,
/// force, the loop's offset across the pull from its braid (empty where no loop is found) and
/// the grip's distance from its target.
fn write_samples(out: &Path, runs: &[PulledKnot]) -> Result<(), String> {
    const HEADER: [&str; 7] = [
        "time_s",
        "end_to_end_cm",
        "force_dyn",
        "loop_x_cm",
        "loop_y_cm",
        "loop_z_cm",
        "grip_error_cm",
    ];
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    for run in runs {
        let path = out.join(format!("n{}_u{}.csv", run.turns, run.end_speed_cm_per_s));
        let mut writer =
            csv::Writer::from_path(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut write = |record: [String; 7]| {
            writer.write_record(record).map_err(|e| format!("{}: {e}", path.display()))
        };
        write(HEADER.map(String::from))?;
        for s in &run.samples {
            let offset = s.loop_offset_cm.map(|o| o.to_array().map(|x| x.to_string()));
            let [x, y, z] = offset.unwrap_or_default();
            write([
                s.time_s.to_string(),
                s.end_to_end_cm.to_string(),
                s.force_dyn.to_string(),
                x,
                y,
                z,
                s.grip_error_cm.to_string(),
            ])?;
        }
        writer.flush().map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_progress_line_names_its_pull_and_outcome() {
        let failed = Err(ValidationError::Scenario { path: "x".into(), reason: "no pull".into() });
        let line = progress((3, 0.6), &failed);
        assert!(line.starts_with("overhand: n = 3, u = 0.6 cm/s: failed"), "{line}");
        assert!(line.contains("no pull"), "{line}");
    }
}
