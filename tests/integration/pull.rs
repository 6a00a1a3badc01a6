//! A pull at prescribed speed (docs/physics.md, "Pulls at prescribed speed (grip)"): the
//! clamped–clamped rod of `data/validation/clamped_buckling.ron`, its tail gripped and pushed
//! toward the head, carries Euler's load 4π²B/L² through its last joint (`internal.csv`, the
//! backward pass over the tree: not the grip's own reading), and a run stopped in the middle
//! of the pull resumes to the same bytes (the grip's anchor is in the checkpoint).

use crate::common::{code_and_stderr, csv_rows, fresh_dir, manifest, run_hagfish};

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

    let stopped = dir.join("stopped");
    let output = run(&stopped, &["--stop-after-frames", "60"]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert_eq!(manifest(&stopped)["status"], "interrupted");
    let resumed = run_hagfish(["run", "--resume", &stopped.to_string_lossy(), "--quiet"]);
    assert!(resumed.status.success(), "{}", code_and_stderr(&resumed).1);
    for file in ["metrics.csv", "internal.csv", "q.npy"] {
        let (a, b) = (std::fs::read(straight.join(file)), std::fs::read(stopped.join(file)));
        assert!(a.expect(file) == b.expect(file), "{file} differs after the resume");
    }
}
