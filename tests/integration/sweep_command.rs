//! `hagfish sweep`: a plan run as two shards and collected gives the same summary as the same
//! plan run with `--jobs 2`; a rerun makes nothing again; grid files with mistakes are
//! refused (exit 2) with the file, line and column or the run and override at fault.

use std::path::Path;

use crate::common::{self, ROOT, code_and_stderr, fresh_dir, run_hagfish};

/// A grid of 4 runs of the thesis scenario (2 time steps × 2 drags; ≈ 1 s each).
fn write_grid(dir: &Path) -> std::path::PathBuf {
    let grid = dir.join("grid.ron");
    let text = format!(
        "Sweep(\n    scenario: \"{ROOT}/data/scenarios/thesis.ron\",\n    grid: [\n        \
         (\"time_step_s\", [\"0.01\", \"0.02\"]),\n        \
         (\"drag.quadratic_g_per_cm3\", [\"0.5\", \"1.0\"]),\n    ],\n    \
         runs: [],\n)\n"
    );
    std::fs::write(&grid, text).expect("grid file");
    grid
}

/// `summary.csv` without its `wall_time_s` column (the only one that differs between equal
/// runs).
fn summary_without_wall_time(folder: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(folder.join("summary.csv")).expect("summary.csv");
    text.lines().map(|line| line.rsplit_once(',').expect("several columns").0.to_owned()).collect()
}

fn ok(args: &[&str]) -> String {
    let output = run_hagfish(args);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(0), "hagfish {}: {stderr}", args.join(" "));
    stderr
}

#[test]
fn two_shards_collect_to_the_summary_of_two_jobs_and_a_rerun_makes_nothing() {
    let dir = fresh_dir("sweep_shards");
    let grid = write_grid(&dir);
    let grid = grid.to_str().expect("UTF-8 path");
    let (sharded, jobs) = (dir.join("sharded"), dir.join("jobs"));
    let (sharded, jobs) = (sharded.to_str().expect("UTF-8"), jobs.to_str().expect("UTF-8"));
    for folder in [sharded, jobs] {
        ok(&["sweep", "plan", grid, "--out", folder]);
    }
    let first = ok(&["sweep", "run", sharded, "--shard", "1/2"]);
    assert!(first.contains("shard 1/2: 2 of the plan's 4 runs"), "{first}");
    ok(&["sweep", "run", sharded, "--shard", "2/2"]);
    ok(&["sweep", "run", jobs, "--jobs", "2"]);
    for folder in [sharded, jobs] {
        ok(&["sweep", "collect", folder]);
    }
    let (a, b) =
        (summary_without_wall_time(Path::new(sharded)), summary_without_wall_time(Path::new(jobs)));
    assert_eq!(a.len(), 5, "a header and 4 runs: {a:?}");
    assert_eq!(a, b);
    assert!(a[1..].iter().all(|row| row.contains(",completed,")), "{a:?}");
    // Each run's final state is the same in both sweeps, bit for bit.
    for id in ["0000", "0001", "0002", "0003"] {
        let hash = |folder: &str| {
            common::manifest(&Path::new(folder).join("runs").join(id))["final_state_hash"].clone()
        };
        assert_eq!(hash(sharded), hash(jobs), "run {id}");
    }
    let rerun = ok(&["sweep", "run", jobs, "--jobs", "2"]);
    assert_eq!(rerun.matches("already completed").count(), 4, "{rerun}");
    assert!(Path::new(jobs).join("plots").read_dir().expect("plots").next().is_some());
}

#[test]
fn mistakes_in_a_grid_are_refused_with_their_place() {
    let dir = fresh_dir("sweep_mistakes");
    let grid = dir.join("bad.ron");
    std::fs::write(
        &grid,
        "Sweep(\n    scenario: \"x.ron\",\n    grid: [(\"time_step_s\" [\"1\"])],\n)\n",
    )
    .expect("grid");
    let output = run_hagfish(["sweep", "plan", grid.to_str().expect("UTF-8"), "--out", "unused"]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("bad.ron:3:"), "{stderr}");

    let grid = dir.join("wrong_path.ron");
    let text = format!(
        "Sweep(scenario: \"{ROOT}/data/scenarios/thesis.ron\", grid: [(\"time_step\", [\"0.01\"])])"
    );
    std::fs::write(&grid, text).expect("grid");
    let out = dir.join("never");
    let output = run_hagfish([
        "sweep",
        "plan",
        grid.to_str().expect("UTF-8"),
        "--out",
        out.to_str().expect("UTF-8"),
    ]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("run 0 (time_step=0.01)") && stderr.contains("time_step"), "{stderr}");
    assert!(!out.exists(), "nothing is written for a plan that is refused");
}
