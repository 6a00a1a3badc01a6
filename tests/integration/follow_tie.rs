//! The follow-the-leader tie (docs/physics.md, "Follow-the-leader tie"; issue #36): on ES103,
//! `figure_eight.ron`'s tie ties 4₁ with its core's head-ward end ≥ 0.35 L, a run stopped in
//! the middle of the tie resumes to the same bytes, and a template that is not a curve, names
//! a knot the analysis does not know or does not fit the body is refused before the run.

use std::path::Path;

use crate::common::{
    assert_resumes_to_the_same_bytes, code_and_stderr, csv_rows, fresh_dir, manifest,
    metrics_table, run_hagfish,
};

/// The first 15 s of `figure_eight.ron` (its tie ends at 13.1 s), into `out`, with `extra`
/// arguments.
fn tie_only(out: &Path, extra: &[&str]) -> std::process::Output {
    let out = out.to_str().expect("a UTF-8 path");
    let mut args = vec!["run", "data/scenarios/figure_eight.ron", "--quiet", "--out", out];
    args.extend(["--set", "duration_s=15.0"]);
    args.extend(extra);
    run_hagfish(args)
}

#[test]
fn the_figure_eight_is_tied_by_following_its_template_and_resumes_bit_for_bit() {
    let dir = fresh_dir("follow_tie");
    let straight = dir.join("straight");
    let output = tie_only(&straight, &[]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert_eq!(manifest(&straight)["status"], "completed");
    let (columns, rows) = metrics_table(&straight);
    let tied = rows.iter().find(|r| r[columns["phase"]] != "tie").expect("the tie ended");
    assert_eq!(tied[columns["knot"]], "4_1");
    let start: f64 = tied[columns["knot_core_start_L"]].parse().expect("a core start");
    assert!(start >= 0.35, "the core starts {start} L from the head");
    let compression: f64 = tied[columns["max_skin_compression"]].parse().expect("a number");
    assert!(compression > 0.0 && compression <= 1.0, "skin compression {compression}");

    let stopped = dir.join("stopped");
    let output = tie_only(&stopped, &["--stop-after-frames", "80"]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert_resumes_to_the_same_bytes(
        &straight,
        &stopped,
        &["metrics.csv", "centreline.csv", "q.npy"],
    );
    assert!(csv_rows(&straight.join("metrics.csv")).len() > 100);
}

#[test]
fn a_template_that_cannot_be_followed_is_refused_before_the_run() {
    let dir = fresh_dir("follow_tie_refused");
    let bad = dir.join("bad.txt");
    let cases = [
        ("0 0 0\n1 x 0\n", "knot: \"4_1\"", "line 2"),
        ("0 0 0\n1 0 0\n2 1 0\n", "knot: \"8_17\"", "not one the knot analysis names"),
        ("0 0 0\n100 0 0\n", "knot: \"4_1\"", "the template is"),
    ];
    for (text, knot, said) in cases {
        std::fs::write(&bad, text).expect("write the template");
        let out = dir.join("run");
        let template =
            format!("phases[0].Follow.template=(file: {:?}, {knot})", bad.display().to_string());
        let output = tie_only(&out, &["--set", &template]);
        let (code, stderr) = code_and_stderr(&output);
        assert_eq!(code, Some(2), "{text}: {stderr}");
        assert!(
            stderr.contains("the knot's template") && stderr.contains(said),
            "{text}: {stderr}"
        );
        assert!(!out.exists(), "{text}: refused before the run directory is made");
    }
}
