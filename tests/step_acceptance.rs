//! A step is kept only if its result is physically valid (`docs/physics.md`, step
//! acceptance): otherwise it is retried as substeps, and failing that the run stops as
//! diverged (exit 3) without recording the bad state. A run stops within a second of SIGTERM
//! even when its frames are far apart.

mod common;

use std::path::Path;
use std::time::{Duration, Instant};

use common::{
    ROOT, code_and_stderr, fresh_dir, hagfish, manifest, metrics_table, run_hagfish, terminate,
};

/// The default bounds: self penetration 10 % of the local radius, limit excess 2°.
const SELF_BOUND: f64 = 0.1;
const LIMIT_BOUND_DEG: f64 = 2.0;

fn thesis() -> String {
    format!("{ROOT}/data/scenarios/thesis_scripted.ron")
}

/// Runs the thesis scenario with `time_step_s` into `dir`.
fn run_thesis_at(dir: &Path, time_step_s: &str) -> std::process::Output {
    let set = format!("time_step_s={time_step_s}");
    run_hagfish(["run", &thesis(), "--quiet", "--out", &dir.to_string_lossy(), "--set", &set])
}

/// Asserts that no recorded frame exceeds the acceptance bounds; returns the frame count.
fn assert_frames_within_bounds(dir: &Path) -> usize {
    let (columns, rows) = metrics_table(dir);
    let (penetration, limit) =
        (columns["max_self_penetration_rel"], columns["max_limit_excess_deg"]);
    for row in &rows {
        let value = |k: usize| row[k].parse::<f64>().expect("a number");
        assert!(
            value(penetration) <= SELF_BOUND,
            "frame {}: penetration {}",
            row[0],
            row[penetration]
        );
        assert!(value(limit) <= LIMIT_BOUND_DEG, "frame {}: limit excess {}", row[0], row[limit]);
    }
    rows.len()
}

#[test]
fn a_coarse_time_step_is_rescued_by_substeps() {
    let dir = fresh_dir("acceptance_h005");
    let output = run_thesis_at(&dir, "0.05");
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(assert_frames_within_bounds(&dir), 301);
    let run = manifest(&dir);
    assert!(run["substepped_steps"].as_u64().expect("a count") >= 1, "{run}");
    assert!(run["max_substeps"].as_u64().expect("a count") >= 2, "{run}");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("taken as substeps"), "{stdout}");
}

#[test]
fn an_absurd_time_step_stops_cleanly_without_recording_a_bad_frame() {
    let dir = fresh_dir("acceptance_h10");
    let output = run_thesis_at(&dir, "10");
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(3), "{stderr}");
    assert!(stderr.contains("result rejected"), "{stderr}");
    assert!(stderr.contains("substeps of"), "the substeps were tried: {stderr}");
    let frames = assert_frames_within_bounds(&dir);
    let run = manifest(&dir);
    assert_eq!(run["status"], "diverged");
    assert_eq!(run["frames"].as_u64(), Some(frames as u64));
    assert!(dir.join("diverged.ron").exists());
}

#[test]
fn sigterm_stops_a_run_with_frames_far_apart_within_a_second() {
    let dir = fresh_dir("acceptance_sigterm");
    // 10⁻⁵ s steps: a frame every 10 000 steps (seconds of wall time apart).
    let child = hagfish([
        "run",
        &thesis(),
        "--quiet",
        "--out",
        &dir.to_string_lossy(),
        "--set",
        "time_step_s=1e-5",
    ])
    .stdout(std::process::Stdio::null())
    .stderr(std::process::Stdio::piped())
    .spawn()
    .expect("hagfish starts");
    let started = Instant::now();
    while csv_rows_if_any(&dir.join("metrics.csv")) < 1 {
        assert!(started.elapsed() < Duration::from_secs(60), "no frame 0 after 60 s");
        std::thread::sleep(Duration::from_millis(5));
    }
    std::thread::sleep(Duration::from_millis(200));
    let signalled = Instant::now();
    terminate(&child);
    let output = child.wait_with_output().expect("the run ends");
    let waited = signalled.elapsed();
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(130), "{stderr}");
    assert!(waited < Duration::from_secs(1), "stopped {waited:?} after SIGTERM");
    assert_eq!(manifest(&dir)["status"], "interrupted");
}

/// Complete rows of a CSV file that may not exist yet or be mid-write.
fn csv_rows_if_any(path: &Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    text.lines().count().saturating_sub(1)
}

#[test]
fn a_chain_blowing_up_without_contact_is_stopped_before_it_is_recorded() {
    // Without water drag the tie's chain goes unstable at h = 0.01 s (docs/physics.md): rates
    // pass 500 rad/s within 0.2 s with no contact or limit involved.
    let dir = fresh_dir("acceptance_vacuum");
    let scenario = format!("{ROOT}/data/scenarios/tie.ron");
    let out = dir.to_string_lossy();
    let output = run_hagfish(["run", &scenario, "--quiet", "--out", &out, "--set", "drag=None"]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(3), "{stderr}");
    assert!(stderr.contains("rad/s (bound 100 rad/s)"), "{stderr}");
    let rates = hagfish_sim::npy::read_npy(&dir.join("qdot.npy")).expect("qdot.npy");
    let fastest = rates.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(fastest <= 100.0, "a recorded frame turns at {fastest} rad/s");
    assert_eq!(manifest(&dir)["status"], "diverged");
}
