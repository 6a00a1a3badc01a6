//! A refusal leaves the run directory exactly as it was (issue 39, item 1): the step cap, a
//! duration too long for it, the memory estimate and a scenario value out of range are all
//! decided before the directory is created, locked or changed, so a completed run stays
//! completed byte for byte (its lock file included) and an absent directory stays absent.

use crate::common::{
    code_and_stderr, es103_with, everything, fresh_dir, manifest, run_hagfish, run_into, short,
};

#[test]
fn refusals_before_the_start_leave_a_completed_run_byte_for_byte() {
    let root = fresh_dir("refusals_completed");
    let dir = root.join("run");
    assert!(run_into(&short(), &dir, &[]).status.success());
    assert_eq!(manifest(&dir)["status"], "completed");
    let before = everything(&dir);
    let huge = es103_with(&root, "huge", &[(" body_count: 100,", " body_count: 100000,".into())]);
    let huge = huge.to_string_lossy().into_owned();
    let cases: [(&[&str], &str); 5] = [
        (&["--overwrite", "--max-steps", "10"], "more than the cap of 10"),
        (&["--max-steps", "10"], "more than the cap of 10"),
        (&["--overwrite", "--set", "duration_s=1e12"], "more than the cap of 100000000"),
        (
            &["--overwrite", "--body", &huge, "--set", "backend=DenseReduced"],
            "a body of 100000 bodies (150000 DOFs) needs about",
        ),
        (&["--overwrite", "--set", "time_step_s=-1"], "time_step_s"),
    ];
    for (extra, expected) in cases {
        let output = run_into(&short(), &dir, extra);
        let (code, stderr) = code_and_stderr(&output);
        assert_eq!(code, Some(2), "{extra:?}: {stderr}");
        assert!(stderr.contains(expected), "{extra:?}: {stderr}");
        assert!(everything(&dir) == before, "{extra:?} changed the completed run");
    }
    // Still the completed run: nothing to resume, and a plain run is refused as before.
    let resumed = run_hagfish(["run", "--resume", &dir.to_string_lossy(), "--quiet"]);
    assert!(code_and_stderr(&resumed).1.contains("the run is completed"));
}

#[test]
fn a_refused_run_leaves_an_absent_directory_absent() {
    let root = fresh_dir("refusals_absent");
    let dir = root.join("never");
    for extra in [&["--max-steps", "10"][..], &["--set", "duration_s=1e12"][..]] {
        let output = run_into(&short(), &dir, extra);
        assert_eq!(code_and_stderr(&output).0, Some(2), "{}", code_and_stderr(&output).1);
        assert!(dir.symlink_metadata().is_err(), "{extra:?} created {}", dir.display());
    }
    // The same arguments without the refusal do make it.
    assert!(run_into(&short(), &dir, &["--stop-after-frames", "1"]).status.success());
    assert_eq!(manifest(&dir)["status"], "interrupted");
}
