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
