//! Huge bodies (issue 39, item 6): a body too large for the memory the process may allocate
//! — its address-space limit included, not only the machine's — is refused before the run
//! directory is touched, with the per-step memory and the limit named (exit 2, never a panic or
//! an abort); and SIGTERM stops a large body's run with a resumable checkpoint.

use std::time::Instant;

use crate::common::{
    code_and_stderr, es103_with, fresh_dir, manifest, run_hagfish, short, stopped_by_sigterm,
    terminate, wait_for_frames,
};

/// Bodies of the large body: 20 000 need ≈ 1.4 GB of step buffers on the sparse backend.
const BODIES: usize = 20_000;

/// ES103 made of [`BODIES`] bodies, written into `dir`.
fn large_body(dir: &std::path::Path) -> String {
    let count = format!(" body_count: {BODIES},");
    let body = es103_with(dir, "large", &[(" body_count: 100,", count)]);
    body.to_string_lossy().into_owned()
}

#[test]
fn an_address_space_limit_refuses_a_large_body_before_the_directory_is_made() {
    let root = fresh_dir("huge_rlimit_as");
    let (body, out) = (large_body(&root), root.join("never"));
    // `prlimit` (util-linux) sets RLIMIT_AS of the command it runs: 1 GiB, as `ulimit -v`.
    let output = std::process::Command::new("prlimit")
        .args(["--as=1073741824", "--", env!("CARGO_BIN_EXE_hagfish"), "run", &short()])
        .args(["--body", &body, "--quiet", "--out", &out.to_string_lossy()])
        .output()
        .expect("prlimit runs hagfish");
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    let expected = format!("a body of {BODIES} bodies (30000 DOFs) needs about");
    assert!(stderr.starts_with(&format!("error: {expected}")), "{stderr}");
    assert!(stderr.contains("RLIMIT_AS"), "the limit is named: {stderr}");
    assert!(stderr.contains("for its step buffers (the memory of every step)"), "{stderr}");
    assert!(!stderr.contains("panicked") && !stderr.contains("memory allocation"), "{stderr}");
    assert!(out.symlink_metadata().is_err(), "a refused run made {}", out.display());
}

#[test]
fn sigterm_stops_a_large_body_with_a_resumable_checkpoint() {
    let root = fresh_dir("huge_sigterm");
    let (body, out) = (large_body(&root), root.join("run"));
    let child = crate::common::hagfish(["run", &short(), "--body", &body, "--quiet", "--out"])
        .arg(&out)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("hagfish starts");
    wait_for_frames(&out, 2);
    let sent = Instant::now();
    terminate(&child);
    let output = child.wait_with_output().expect("the run ends");
    // Measured, not asserted (a loaded machine makes any bound flaky):
    // docs/measurements/2026-11-28-sigterm-latency.md.
    eprintln!("{BODIES} bodies: SIGTERM to exit {:.3} s", sent.elapsed().as_secs_f64());
    let frames = stopped_by_sigterm(&output, &out);
    assert!(frames >= 2, "{frames}: frames 0 and 1 were on disk");
    // Resumable from its checkpoint: one more frame, then stopped again.
    let resumed = run_hagfish([
        "run",
        "--resume",
        &out.to_string_lossy(),
        "--quiet",
        "--stop-after-frames",
        &frames.to_string(),
    ]);
    assert!(resumed.status.success(), "{}", code_and_stderr(&resumed).1);
    let again = manifest(&out);
    assert_eq!(
        (again["status"].as_str(), again["frames"].as_u64()),
        (Some("interrupted"), Some(frames + 1))
    );
    assert_eq!(again["resumed_at_frames"][0].as_u64(), Some(frames));
}
