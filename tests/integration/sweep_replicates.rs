//! Replicated sweeps: each grid point run at rounding perturbations of its time step, planned
//! again with more replicates without making any run twice, and collected into per-point
//! intervals that hold what their runs say.

use std::path::Path;

use crate::common::{ROOT, code_and_stderr, fresh_dir, run_hagfish};

/// A grid of 2 drags of the thesis scenario with `replicates` runs each.
fn write_grid(dir: &Path, replicates: usize) -> String {
    let grid = dir.join(format!("grid{replicates}.ron"));
    let text = format!(
        "Sweep(\n    scenario: \"{ROOT}/data/scenarios/thesis.ron\",\n    grid: [\n        \
         (\"drag.quadratic_g_per_cm3\", [\"0.5\", \"1.0\"]),\n    ],\n    replicates: {replicates},\n)\n"
    );
    std::fs::write(&grid, text).expect("grid file");
    grid.to_str().expect("UTF-8 path").to_owned()
}

fn ok(args: &[&str]) -> String {
    let output = run_hagfish(args);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(0), "hagfish {}: {stderr}", args.join(" "));
    String::from_utf8_lossy(&output.stdout).into_owned() + &stderr
}

/// The rows of a CSV file as maps from column to value.
fn table(path: &Path) -> Vec<std::collections::BTreeMap<String, String>> {
    let mut reader = csv::Reader::from_path(path).expect("a CSV file");
    let header = reader.headers().expect("a header").clone();
    reader
        .records()
        .map(|r| {
            let r = r.expect("a record");
            header.iter().zip(r.iter()).map(|(h, v)| (h.to_owned(), v.to_owned())).collect()
        })
        .collect()
}

#[test]
fn more_replicates_make_only_the_new_runs_and_the_intervals_hold_their_runs() {
    let dir = fresh_dir("sweep_replicates");
    let folder = dir.join("sweep");
    let out = folder.to_str().expect("UTF-8");
    let planned = ok(&["sweep", "plan", &write_grid(&dir, 4), "--out", out]);
    assert!(planned.contains("8 runs (2 grid points × 4 replicates)"), "{planned}");
    ok(&["sweep", "run", out, "--jobs", "2"]);
    ok(&["sweep", "plan", &write_grid(&dir, 5), "--out", out]);
    let rerun = ok(&["sweep", "run", out, "--jobs", "2"]);
    assert_eq!(rerun.matches("already completed").count(), 8, "{rerun}");
    assert!(rerun.contains("run 0000-4 ") && rerun.contains("run 0001-4 "), "{rerun}");
    let collected = ok(&["sweep", "collect", out]);
    assert!(
        collected.contains("point 1 (drag.quadratic_g_per_cm3=1.0): 5 runs ended"),
        "{collected}"
    );

    let runs = table(&folder.join("summary.csv"));
    let ids: Vec<&str> = runs.iter().map(|r| r["id"].as_str()).collect();
    assert_eq!(ids[..6], ["0000", "0000-1", "0000-2", "0000-3", "0000-4", "0001"]);
    let replicates: Vec<&str> = runs.iter().map(|r| r["replicate"].as_str()).collect();
    assert_eq!(replicates, ["0", "1", "2", "3", "4", "0", "1", "2", "3", "4"]);
    // Replicates differ at rounding level: their final states differ, their knots do not.
    let hash = |id: &str| {
        crate::common::manifest(&folder.join("runs").join(id))["final_state_hash"].clone()
    };
    assert_ne!(hash("0000"), hash("0000-1"));

    let intervals = table(&folder.join("intervals.csv"));
    for point in ["0", "1"] {
        let of_point: Vec<_> = runs.iter().filter(|r| r["point"] == point).collect();
        let row = |statistic: &str| {
            intervals
                .iter()
                .find(|r| r["point"] == point && r["statistic"] == statistic)
                .unwrap_or_else(|| panic!("point {point}: no {statistic}"))
        };
        let travel = row("core_travel_L");
        assert_eq!((travel["runs"].as_str(), travel["n"].as_str()), ("5", "5"));
        let values: Vec<f64> =
            of_point.iter().map(|r| r["core_travel_L"].parse().expect("a travel")).collect();
        let mean: f64 = values.iter().sum::<f64>() / 5.0;
        let number = |k: &str| travel[k].parse::<f64>().expect("a number");
        assert!((number("mean") - mean).abs() < 1e-12 * mean.abs().max(1.0));
        assert!(number("ci_low") <= number("ci_high"));
        // The interval is of the spread's scale, not a guess: within 10 sd of the mean.
        let sd = number("sd");
        assert!(sd > 0.0 && number("ci_high") - number("ci_low") < 10.0 * sd, "{travel:?}");
        let tied = row("tied_share");
        let share = of_point.iter().filter(|r| !r["tied_at_s"].is_empty()).count() as f64 / 5.0;
        assert_eq!(tied["mean"].parse::<f64>().expect("a share"), share);
        let (low, high): (f64, f64) =
            (tied["ci_low"].parse().expect("low"), tied["ci_high"].parse().expect("high"));
        assert!(low <= share && share <= high && high <= 1.0 && low >= 0.0, "{tied:?}");
    }
    assert!(folder.join("plots").join("core_travel_L_vs_drag_quadratic_g_per_cm3.svg").exists());

    // Fewer replicates than the folder holds is another plan: refused.
    let output = run_hagfish(["sweep", "plan", &write_grid(&dir, 2), "--out", out]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("holds another plan"), "{stderr}");
}
