//! Knot plans as files (docs/knot-plans.md): a scenario that names the built-in overhand
//! plan's file ties exactly what the built-in knot ties, as written and mirrored, and a plan
//! that is not one is refused at load with the plan file's position.

use std::path::Path;

use crate::common::{code_and_stderr, fresh_dir, run_hagfish};

/// `hagfish run data/scenarios/tie.ron --quiet --out OUT --set phases[0].Tie.knot=KNOT`
/// (`tie.ron` ties a right-handed trefoil by control).
fn run_tie_with(out: &Path, knot: &str) -> std::process::Output {
    let out = out.to_str().expect("a UTF-8 path");
    let set = format!("phases[0].Tie.knot={knot}");
    run_hagfish(["run", "data/scenarios/tie.ron", "--quiet", "--out", out, "--set", &set])
}

/// [`run_tie_with`] into `dir/name`: the bytes of its metrics.csv.
fn tie_metrics(dir: &Path, name: &str, knot: &str) -> Vec<u8> {
    let out = dir.join(name);
    let output = run_tie_with(&out, knot);
    assert!(output.status.success(), "{name}: {}", code_and_stderr(&output).1);
    std::fs::read(out.join("metrics.csv")).expect("metrics.csv")
}

#[test]
fn the_overhand_plan_file_ties_the_built_in_trefoil_bit_for_bit_and_its_mirror_image() {
    let dir = fresh_dir("knot_plans");
    let file = "Planned((file: \"../knots/overhand.ron\"))";
    let mirrored = "Planned((file: \"../knots/overhand.ron\", mirror: true))";
    let right = tie_metrics(&dir, "right", "Trefoil(Right)");
    assert_eq!(tie_metrics(&dir, "planned", file), right, "the file is the built-in plan");
    let left = tie_metrics(&dir, "left", "Trefoil(Left)");
    assert_ne!(left, right, "the mirror image ties another way");
    assert_eq!(tie_metrics(&dir, "planned_mirror", mirrored), left);
}

#[test]
fn a_plan_that_is_not_one_is_refused_before_the_run_with_its_position() {
    let dir = fresh_dir("knot_plans_refused");
    let plan = dir.join("bad.ron");
    let cases = [
        (
            "(knot: \"6_2\", handedness: None, steps: [(name: \"x\", action: Jump(1.0))])",
            "bad.ron:1:",
        ),
        ("(knot: \"six\", handedness: None, steps: [(name: \"x\", action: Hold(1.0))])", "Rolfsen"),
        (
            "(knot: \"6_2\", handedness: None, steps: [(name: \"x\", action: Hold(-1.0))])",
            "negative",
        ),
    ];
    for (text, said) in cases {
        std::fs::write(&plan, text).expect("write the plan");
        let out = dir.join("run");
        let output =
            run_tie_with(&out, &format!("Planned((file: {:?}))", plan.display().to_string()));
        let (code, stderr) = code_and_stderr(&output);
        assert_eq!(code, Some(2), "{text}: {stderr}");
        assert!(stderr.contains("the knot's plan") && stderr.contains(said), "{text}: {stderr}");
        assert!(!out.exists(), "{text}: refused before the run directory is made");
    }
}

/// The frames whose `thigmo` group in `dir`'s forces.csv is not all zero, among the frames of
/// metrics.csv's `phase` = `tie`.
fn tie_frames_with_force(dir: &Path) -> (usize, usize) {
    let (columns, rows) = crate::common::metrics_table(dir);
    let phase = columns["phase"];
    let forces = crate::common::csv_rows(&dir.join("forces.csv"));
    let tie_frames: Vec<&String> =
        rows.iter().filter(|r| r[phase] == "tie").map(|r| &r[0]).collect();
    let pushed = tie_frames
        .iter()
        .filter(|frame| {
            forces.iter().any(|f| {
                f[0].as_str() == frame.as_str()
                    && f[4] == "thigmo"
                    && f[5].parse::<f64>() != Ok(0.0)
            })
        })
        .count();
    (pushed, tie_frames.len())
}

/// `figure_eight.ron` tied by its plan of waypoints on the rigid tube, holding the crossings it
/// has made (`hold_crossings_dyn`): hold rows push during the tie (the `thigmo` group of forces.csv),
/// where the same tie without holds pushes nothing; and a run stopped after the first hold
/// resumes bit for bit (the held crossings are in the checkpoint).
#[test]
fn a_tie_that_holds_its_crossings_pushes_on_them_and_resumes_bit_for_bit() {
    let dir = fresh_dir("knot_plans_hold");
    let scenario = "data/scenarios/figure_eight.ron";
    let hold = "phases[0].Tie.hold_crossings_dyn=Some(1000.0)";
    let plan = "phases[0]=Tie((knot: FigureEight, at: 0.31, min_tail_d: Some(18.5)))";
    let run = |name: &str, extra: &[&str]| {
        let out = dir.join(name);
        let mut args = vec!["run", scenario, "--quiet", "--out", out.to_str().expect("UTF-8")];
        args.extend_from_slice(&["--set", plan, "--set", "skin=None"]);
        args.extend_from_slice(&["--set", "end_after_phases=false", "--set", "duration_s=21.0"]);
        args.extend_from_slice(extra);
        let output = run_hagfish(args);
        assert!(output.status.success(), "{name}: {}", code_and_stderr(&output).1);
        out
    };
    let held = run("held", &["--set", hold]);
    let free = run("free", &[]);
    let (pushed, frames) = tie_frames_with_force(&held);
    assert!(pushed >= 5, "hold rows pushed on {pushed} of {frames} tie frames");
    assert_eq!(tie_frames_with_force(&free).0, 0, "no hold, no thigmotaxis in a tie");

    // Frame 180 (18 s): the holds push from 17.1 s on (measured on this run).
    let stopped = run("stopped", &["--set", hold, "--stop-after-frames", "180"]);
    let resumed = run_hagfish(["run", "--resume", stopped.to_str().expect("UTF-8"), "--quiet"]);
    assert!(resumed.status.success(), "{}", code_and_stderr(&resumed).1);
    for file in ["q.npy", "qdot.npy", "metrics.csv", "forces.csv"] {
        let (a, b) = (std::fs::read(held.join(file)), std::fs::read(stopped.join(file)));
        assert!(a.expect(file) == b.expect(file), "{file} differs after the resume");
    }
}

#[test]
fn a_resume_refuses_a_knot_plan_edited_since_the_checkpoint() {
    let dir = fresh_dir("knot_plans_edited");
    let plan = dir.join("overhand.ron");
    std::fs::copy("data/knots/overhand.ron", &plan).expect("copy the plan");
    let out = dir.join("out");
    let knot = format!("Planned((file: {:?}))", plan.to_str().expect("UTF-8"));
    let stopped = run_hagfish([
        "run",
        "data/scenarios/tie.ron",
        "--quiet",
        "--out",
        out.to_str().expect("UTF-8"),
        "--set",
        &format!("phases[0].Tie.knot={knot}"),
        "--stop-after-frames",
        "5",
    ]);
    assert!(stopped.status.success(), "{}", code_and_stderr(&stopped).1);
    let resume = || run_hagfish(["run", "--resume", out.to_str().expect("UTF-8"), "--quiet"]);
    let text = std::fs::read_to_string(&plan).expect("the plan");
    std::fs::write(&plan, text.clone() + "// an edit\n").expect("edit the plan");
    let (code, stderr) = code_and_stderr(&resume());
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("a knot plan, modal basis or replay file"), "{stderr}");
    // Put back, the same plan resumes.
    std::fs::write(&plan, text).expect("restore the plan");
    let resumed = resume();
    assert!(resumed.status.success(), "{}", code_and_stderr(&resumed).1);
}
