//! Checkpoint and resume, end to end on `data/scenarios/form.ron` (3000 steps, 301 frames):
//!
//! - stopped after frame 200 (`--stop-after-frames`, status `interrupted`) and resumed, the run
//!   gives the same bytes in every output and the same final-state hash as a straight run;
//! - killed with SIGKILL mid-way, it leaves CSV files of whole frames up to the frame being
//!   written (which the kill may cut, even mid-row: Linux stops a write between pages when
//!   SIGKILL arrives), frame counts that agree across files (up to that frame) and cover the
//!   checkpoint, and resumed from there it again ends bit for bit as the straight run;
//! - stopped by SIGTERM, it ends after a frame with exit code 130, status `interrupted`, and
//!   resumes bit for bit;
//! - `thesis.ron` with friction and an obstacle, stopped after frame 120 and resumed, gives the
//!   straight run's bytes;
//! - `slide.ron` stopped mid-slide and resumed gives the straight run's bytes.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::common::{
    ROOT, code_and_stderr, complete_rows, csv_rows, frames_of, fresh_dir, hagfish, manifest,
    run_hagfish, stopped_by_sigterm, terminate, wait_for_frames,
};

const OUTPUTS: [&str; 7] = [
    "centreline.csv",
    "metrics.csv",
    "forces.csv",
    "contacts.csv",
    "q.npy",
    "qdot.npy",
    "thigmo_force.npy",
];

fn scenario() -> String {
    format!("{ROOT}/data/scenarios/form.ron")
}

/// Runs form.ron straight once per test binary.
fn straight() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = fresh_dir("resume_straight");
        let output = run_hagfish(["run", &scenario(), "--quiet", "--out", &dir.to_string_lossy()]);
        assert!(output.status.success(), "{}", code_and_stderr(&output).1);
        dir
    })
}

/// Runs `scenario` with the `extra` arguments into a fresh directory named `name`.
fn run_into(name: &str, scenario: &str, extra: &[&str]) -> PathBuf {
    let dir = fresh_dir(name);
    let out = dir.to_string_lossy().into_owned();
    let mut args = vec!["run", scenario, "--quiet", "--out", &out];
    args.extend(extra);
    let output = run_hagfish(args);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    dir
}

fn resume(dir: &Path) {
    let output = run_hagfish(["run", "--resume", &dir.to_string_lossy(), "--quiet"]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
}

/// Every output file and the manifest's counts and final-state hash are identical.
fn assert_same_as_straight(dir: &Path) {
    let reference = straight();
    for file in OUTPUTS {
        let a = std::fs::read(reference.join(file)).expect(file);
        let b = std::fs::read(dir.join(file)).expect(file);
        assert!(a.len() > 128 && a == b, "{file} differs from the straight run");
    }
    let (a, b) = (manifest(reference), manifest(dir));
    assert_eq!(b["status"], "completed");
    for key in ["steps", "frames", "final_state_hash", "scenario_hash"] {
        assert_eq!(a[key], b[key], "{key}");
    }
    assert_eq!(a["steps"], 3000);
}

/// The arrays have one row per frame, and the last rows of q and q̇ are the state saved in the
/// final checkpoint, bit for bit.
fn assert_arrays_end_at_the_checkpoint(dir: &Path) {
    let checkpoint = std::fs::read_to_string(dir.join("checkpoint.ron")).expect("checkpoint");
    for (file, key) in [("q.npy", "q: "), ("qdot.npy", "qdot: ")] {
        let array = hagfish_run::npy::read_npy(&dir.join(file)).expect(file);
        assert_eq!((array.rows, array.columns), (301, 150), "{file}");
        let saved: Vec<u64> = checkpoint
            .lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .expect(key)
            .trim_matches(|c| c == '"' || c == ',')
            .split_whitespace()
            .map(|w| u64::from_str_radix(w, 16).expect("hex"))
            .collect();
        let last: Vec<u64> = array.values[300 * 150..].iter().map(|v| v.to_bits()).collect();
        assert_eq!(saved, last, "{file}");
    }
}

#[test]
fn stop_and_resume_gives_the_straight_run_bit_for_bit() {
    let dir = fresh_dir("resume_stopped");
    let dir_arg = dir.to_string_lossy().into_owned();
    let output = run_hagfish([
        "run",
        &scenario(),
        "--quiet",
        "--out",
        &dir_arg,
        "--stop-after-frames",
        "200",
    ]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let stopped = manifest(&dir);
    assert_eq!(stopped["status"], "interrupted");
    assert_eq!((stopped["frames"].as_u64(), stopped["steps"].as_u64()), (Some(201), Some(2000)));
    assert_eq!(frames_of(&csv_rows(&dir.join("metrics.csv"))).last(), Some(&200));
    resume(&dir);
    assert_same_as_straight(&dir);
    assert_arrays_end_at_the_checkpoint(&dir);
    assert_eq!(manifest(&dir)["resumed_at_frames"], serde_json::json!([201]));

    let again = run_hagfish(["run", "--resume", &dir_arg]);
    let (code, stderr) = code_and_stderr(&again);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("the run is completed: nothing to resume"), "{stderr}");
}

/// Asserts that `frames` (the frame of each row) are `per_frame` rows of frame 0, then of
/// frame 1, and so on: whole frames, the last of which may be cut short.
fn assert_frame_major(frames: &[usize], per_frame: usize, file: &str) {
    let expected: Vec<usize> = (0..frames.len()).map(|k| k / per_frame).collect();
    assert_eq!(frames, expected, "{file}: whole frames in order, the last possibly cut");
}

#[test]
fn a_killed_run_keeps_whole_frames_and_resumes_bit_for_bit() {
    let dir = fresh_dir("resume_killed");
    let mut child = hagfish(["run", &scenario(), "--quiet", "--out", &dir.to_string_lossy()])
        .stdout(std::process::Stdio::null())
        .spawn()
        .expect("hagfish starts");
    wait_for_frames(&dir, 150);
    child.kill().expect("SIGKILL");
    child.wait().expect("the killed run is reaped");
    assert_eq!(manifest(&dir)["status"], "running", "the run ended before it was killed");

    let metrics = frames_of(&complete_rows(&dir.join("metrics.csv")));
    let frames = metrics.len();
    assert_eq!(metrics, (0..frames).collect::<Vec<_>>(), "metrics.csv: frames 0, 1, …");
    let centreline = frames_of(&complete_rows(&dir.join("centreline.csv")));
    assert_frame_major(&centreline, 100, "centreline.csv");
    let forces = frames_of(&complete_rows(&dir.join("forces.csv")));
    assert_frame_major(&forces, 3 * 150, "forces.csv");
    let contacts = frames_of(&complete_rows(&dir.join("contacts.csv")));
    let checkpoint = std::fs::read_to_string(dir.join("checkpoint.ron")).expect("checkpoint");
    let saved: usize = checkpoint
        .lines()
        .find_map(|l| l.trim().strip_prefix("frames: "))
        .and_then(|v| v.trim_end_matches(',').parse().ok())
        .expect("frames in the checkpoint");
    // Files are written in this order, each frame in one write: centreline, metrics, forces,
    // contacts, then the arrays; a kill between two writes leaves one file a frame ahead.
    let counts = [centreline.len() / 100, frames, forces.len() / 450];
    assert!(counts.iter().all(|&c| c >= saved && c <= saved + 1), "{counts:?} vs {saved}");
    assert!(contacts.last().is_none_or(|&f| f <= centreline.len() / 100));
    for file in ["q.npy", "qdot.npy", "thigmo_force.npy"] {
        let array = hagfish_run::npy::read_npy(&dir.join(file)).expect(file);
        assert!(array.rows >= saved && array.rows <= saved + 1, "{file}: {}", array.rows);
        assert_eq!(array.columns, 150);
    }

    resume(&dir);
    assert_same_as_straight(&dir);
}

#[test]
fn resume_flag_starts_a_missing_run_and_refuses_another_scenario() {
    let dir = fresh_dir("resume_flag");
    let dir_arg = dir.to_string_lossy().into_owned();
    let short = format!("{ROOT}/tests/data/form.ron");
    let args = |scenario: &str, extra: &[&str]| {
        let mut args = vec!["run", "--quiet", "--resume", "--out", &dir_arg];
        args.insert(1, scenario);
        args.extend_from_slice(extra);
        args.into_iter().map(str::to_owned).collect::<Vec<_>>()
    };
    let first = run_hagfish(args(&short, &["--stop-after-frames", "5"]));
    assert!(first.status.success(), "{}", code_and_stderr(&first).1);
    assert_eq!(manifest(&dir)["status"], "interrupted");

    let other = run_hagfish(args(&scenario(), &[]));
    let (code, stderr) = code_and_stderr(&other);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("the run is of another scenario"), "{stderr}");

    let second = run_hagfish(args(&short, &[]));
    assert!(second.status.success(), "{}", code_and_stderr(&second).1);
    let done = manifest(&dir);
    assert_eq!((done["status"].as_str(), done["frames"].as_u64()), (Some("completed"), Some(16)));
    assert_eq!(done["resumed_at_frames"], serde_json::json!([6]));
}

#[test]
fn sigterm_stops_after_a_frame_with_a_resumable_run() {
    let dir = fresh_dir("resume_sigterm");
    let child = hagfish(["run", &scenario(), "--quiet", "--out", &dir.to_string_lossy()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("hagfish starts");
    wait_for_frames(&dir, 100);
    terminate(&child);
    let output = child.wait_with_output().expect("the run ends");
    let frames = stopped_by_sigterm(&output, &dir);
    // 100 frames were on disk when the signal was sent; the run finishes the frame it is in
    // (or none, if the signal arrived between a frame's rows and the check after it) and
    // stops before the last of its 301.
    assert!((100..301).contains(&frames), "{frames}");
    assert_eq!(csv_rows(&dir.join("metrics.csv")).len() as u64, frames);

    resume(&dir);
    assert_same_as_straight(&dir);
}

#[test]
fn a_run_with_friction_and_an_obstacle_resumes_bit_for_bit() {
    let scenario = format!("{ROOT}/data/scenarios/thesis.ron");
    let sets = [
        "--set",
        "friction=Some((coefficient: 0.1))",
        "--set",
        "obstacles=[Sphere(centre: (20.0, -3.0, 0.0), radius: 1.5)]",
    ];
    let straight = run_into("friction_straight", &scenario, &sets);
    let stopped = run_into(
        "friction_stopped",
        &scenario,
        &[&sets[..], &["--stop-after-frames", "120"]].concat(),
    );
    assert_eq!(manifest(&stopped)["status"], "interrupted");
    resume(&stopped);
    for file in ["metrics.csv", "centreline.csv", "contacts.csv", "q.npy"] {
        let (a, b) = (std::fs::read(straight.join(file)), std::fs::read(stopped.join(file)));
        assert!(a.expect(file) == b.expect(file), "{file} differs after the resume");
    }
    assert_eq!(manifest(&straight)["final_state_hash"], manifest(&stopped)["final_state_hash"]);
}

/// `slide.ron` stopped mid-slide (frame 220 of 260: the knot tied since 16.3 s, thigmotaxis
/// sliding it) and resumed: the checkpoint carries the velocity solve's warm start (the
/// multipliers of the knot's contact and thigmotaxis rows, keyed by the contacts' spline
/// parameters and the rows' ids), and the resumed run gives the straight run's bytes.
#[test]
fn a_run_stopped_mid_slide_resumes_bit_for_bit() {
    let scenario = format!("{ROOT}/data/scenarios/slide.ron");
    let straight = run_into("slide_straight", &scenario, &[]);
    let stopped = run_into("slide_stopped", &scenario, &["--stop-after-frames", "220"]);
    let checkpoint = hagfish_run::Checkpoint::read(&stopped.join(hagfish_run::CHECKPOINT_FILE))
        .expect("the stopped run's checkpoint");
    assert_eq!(checkpoint.controller.phases.phase, 1, "stopped in the slide phase");
    let carried = checkpoint.warm_start.multipliers().expect("three values a row");
    let pushing = carried.iter().filter(|m| m.lambda > 0.0).count();
    assert!(pushing >= 4, "rows pushing at the checkpoint: {pushing}");
    let contact = hagfish_sim::rows::RowGroup::Contact.tag().index() as u8;
    let contacts = carried.iter().filter(|m| m.key.group == contact && m.lambda > 0.0);
    assert!(contacts.count() >= 1, "no contact row pushing at the checkpoint");
    resume(&stopped);
    for file in OUTPUTS {
        let (a, b) = (std::fs::read(straight.join(file)), std::fs::read(stopped.join(file)));
        assert!(a.expect(file) == b.expect(file), "{file} differs after the resume");
    }
    assert_eq!(manifest(&straight)["final_state_hash"], manifest(&stopped)["final_state_hash"]);
}
