//! A pull at prescribed speed (docs/physics.md, "Pulls at prescribed speed (grip)"): the
//! clamped–clamped rod of `data/validation/clamped_buckling.ron`, its tail gripped and pushed
//! toward the head, carries Euler's load 4π²B/L² through its last joint (`internal.csv`, the
//! backward pass over the tree: not the grip's own reading), which is the grip's push in
//! `metrics.csv`; and a run stopped in the middle of the pull resumes to the same bytes (the
//! grip's anchor is in the checkpoint).

use crate::common::{
    assert_resumes_to_the_same_bytes, code_and_stderr, csv_rows, fresh_dir, manifest, run_hagfish,
};

#[test]
fn a_gripped_rod_carries_euler_s_load_and_resumes_mid_pull_bit_for_bit() {
    let dir = fresh_dir("pull");
    let run = |out: &std::path::Path, extra: &[&str]| {
        let out = out.to_str().expect("a UTF-8 path");
        let mut args = vec!["run", "data/validation/clamped_buckling.ron", "--quiet", "--out", out];
        args.extend(extra);
        run_hagfish(args)
    };
    let straight = dir.join("straight");
    let output = run(&straight, &[]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert_eq!(manifest(&straight)["status"], "completed");
    // The last frame's last joint (the rod's 100 bodies: joint 99), 1.9 % shortened.
    let rows = csv_rows(&straight.join("internal.csv"));
    let last = rows.iter().rev().find(|r| r[2] == "99").expect("the last joint");
    let tension: f64 = last[4].parse().expect("a tension");
    let euler = 4.0 * std::f64::consts::PI.powi(2) * 490.9 / 100.0;
    assert!((-tension / euler - 1.0).abs() < 0.02, "compression {} against {euler}", -tension);
    // The grip's own reading in metrics.csv: the push on the rod's end, toward the head, is
    // the load its last joint carries.
    let header = std::fs::read_to_string(straight.join("metrics.csv")).expect("metrics.csv");
    let header = header.lines().next().expect("a header");
    let column = header.split(',').position(|c| c == "grip_force_x_dyn").expect("grip force");
    let metrics = csv_rows(&straight.join("metrics.csv"));
    let push: f64 = metrics.last().expect("a frame")[column].parse().expect("a force");
    assert!((push / tension - 1.0).abs() < 1e-3, "grip {push} against the last joint's {tension}");

    let stopped = dir.join("stopped");
    let output = run(&stopped, &["--stop-after-frames", "60"]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert_resumes_to_the_same_bytes(
        &straight,
        &stopped,
        &["metrics.csv", "internal.csv", "q.npy"],
    );
}
