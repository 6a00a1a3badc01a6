//! `hagfish run SCENARIO --set PATH=VALUE --body FILE`: overrides for studies, end to end.

use std::path::Path;

use crate::common::{ROOT, code_and_stderr, fresh_dir, manifest, run_hagfish};

/// Runs the short forming scenario into `out` with `extra` arguments.
fn run_form(out: &Path, extra: &[&str]) -> std::process::Output {
    let scenario = format!("{ROOT}/tests/data/form.ron");
    let mut args = vec!["run", scenario.as_str(), "--quiet", "--out"];
    let out = out.display().to_string();
    args.push(&out);
    args.extend_from_slice(extra);
    run_hagfish(args)
}

/// The lines of `scenario.ron` in run directory `dir`.
fn scenario_lines(dir: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(dir.join("scenario.ron")).expect("scenario.ron");
    text.lines().map(str::to_owned).collect()
}

#[test]
fn an_override_changes_what_it_names_and_nothing_else() {
    let dir = fresh_dir("overrides_one");
    let (plain, changed) = (dir.join("plain"), dir.join("changed"));
    assert!(run_form(&plain, &[]).status.success());
    let output = run_form(&changed, &["--set", "time_step_s=0.02"]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let (before, after) = (scenario_lines(&plain), scenario_lines(&changed));
    assert_eq!(before.len(), after.len());
    let differing: Vec<(&String, &String)> =
        before.iter().zip(&after).filter(|(a, b)| a != b).collect();
    assert_eq!(differing.len(), 1, "{differing:?}");
    assert_eq!(differing[0].1.trim(), "time_step_s: 0.02,");
    assert_eq!(manifest(&changed)["overrides"][0], "time_step_s=0.02");
    assert_eq!(manifest(&changed)["steps"], 75, "1.5 s at 0.02 s");
    assert_eq!(manifest(&plain)["overrides"].as_array().map(Vec::len), Some(0));
}

#[test]
fn a_body_file_replaces_the_scenarios_body() {
    let dir = fresh_dir("overrides_body");
    let es103 = std::fs::read_to_string(format!("{ROOT}/data/hagfish/es103.ron")).expect("es103");
    let body = dir.join("fifty.ron");
    std::fs::write(&body, es103.replace(" body_count: 100,", " body_count: 50,")).expect("write");
    let out = dir.join("run");
    let output = run_form(&out, &["--body", body.to_str().expect("UTF-8 path")]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let recorded = format!("body: {:?},", body.display().to_string());
    assert!(scenario_lines(&out).iter().any(|l| l.trim() == recorded), "{recorded}");
    let q = std::fs::read(out.join("q.npy")).expect("q.npy");
    assert!(String::from_utf8_lossy(&q[..128]).contains(", 75)"), "50 bodies = 75 DOFs");
}

#[test]
fn bad_overrides_are_exit_2_naming_the_override() {
    let dir = fresh_dir("overrides_bad");
    let cases = [
        ("time_stepp=0.02", "error: --set time_stepp=0.02: no field `time_stepp`"),
        ("time_step_s=fast", "error: --set time_step_s=fast: wrong value for time_step_s"),
        ("time_step_s=-1", "error: with --set time_step_s=-1: "),
        ("Thigmotaxis.parameters.tail_pull_dyn=1", "the scenario has no Thigmotaxis phase"),
        ("phases[3].Form.gains.kp_dyn_per_cm=1", "no [3]"),
        ("duration_s", "expected PATH=VALUE"),
    ];
    for (given, expected) in cases {
        let output = run_form(&dir.join("run"), &["--set", given]);
        let (code, stderr) = code_and_stderr(&output);
        assert_eq!(code, Some(2), "{given}: {stderr}");
        assert!(stderr.contains(expected), "{given}: expected {expected:?} in {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    let output = run_hagfish(["run", "--resume", "somewhere", "--set", "time_step_s=1"]);
    assert_eq!(code_and_stderr(&output).0, Some(2));
}

/// A knot-size end condition out of its range is exit 2 at its place in the overridden text:
/// sizes in diameters > 0, growth > 0, shrinkage a proportion in (0, 1). A whole list of
/// conditions or one condition by its index can be set.
#[test]
fn knot_size_end_conditions_are_checked() {
    let dir = fresh_dir("overrides_knot_size");
    let scenario = format!("{ROOT}/data/scenarios/loosen_tighten.ron");
    let cases = [
        ("phases[1].Thigmotaxis.until.when=[(CoreLength, Above, D(0.0))]", "when.D = 0"),
        ("phases[2].Thigmotaxis.until.when=[(CoreLength, Below, D(-1.0))]", "when.D = -1"),
        (
            "phases[1].Thigmotaxis.until.when[0]=(CoreGrowth, Above, Fraction(-0.5))",
            "expected finite and > 0",
        ),
        (
            "phases[2].Thigmotaxis.until.when[0]=(CoreShrink, Above, Fraction(1.5))",
            "expected a proportion in (0, 1)",
        ),
        ("phases[1].Thigmotaxis.until.when=[(Span, Above, D(0.0))]", "when.D = 0"),
    ];
    for (given, expected) in cases {
        let out = dir.join("run").display().to_string();
        let output = run_hagfish(["run", &scenario, "--quiet", "--out", &out, "--set", given]);
        let (code, stderr) = code_and_stderr(&output);
        assert_eq!(code, Some(2), "{given}: {stderr}");
        assert!(stderr.contains("[with overrides]:"), "{given}: no location in {stderr}");
        assert!(stderr.contains(expected), "{given}: expected {expected:?} in {stderr}");
    }
    // A quantity in a unit it cannot be read in is refused, naming what it admits.
    let given = "phases[1].Thigmotaxis.until.when[0]=(KnotStart, Below, D(3.0))";
    let out = dir.join("run").display().to_string();
    let output = run_hagfish(["run", &scenario, "--quiet", "--out", &out, "--set", given]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    let expected = "(KnotStart, Below, D(…)) is not an end condition: KnotStart is compared \
                    Below or Above, in Cm or L";
    assert!(stderr.contains(expected), "expected {expected:?} in {stderr}");
}

#[test]
fn a_phase_name_with_a_comma_stays_one_field_and_the_report_reads_it() {
    let dir = fresh_dir("comma_in_phase_name");
    let run = dir.join("run");
    let targets = "(v_a: 0.0, v_b: 0.0)";
    let phase = format!(
        "phases=[Thigmotaxis((name: \"a,b\", parameters: (head: {targets}, tail: {targets}, \
         tail_pull_dyn: 0.0, max_force_dyn: 100.0), until: (seconds: 0.5)))]"
    );
    let output = run_form(&run, &["--set", &phase]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(0), "{stderr}");
    let metrics = hagfish_report::CsvFile::open(&run.join("metrics.csv")).expect("metrics.csv");
    let column = metrics.column("phase").expect("a phase column");
    let mut phases = Vec::new();
    metrics
        .for_each_record(|record| {
            phases.push(record.text(column).to_owned());
            Ok(())
        })
        .expect("every row as wide as the header");
    assert!(phases.iter().any(|p| p == "a,b"), "{phases:?}");
    let report = run_hagfish(["report", run.to_str().expect("a UTF-8 path")]);
    let (code, stderr) = code_and_stderr(&report);
    assert_eq!(code, Some(0), "hagfish report: {stderr}");
}

/// A 100 kB value is echoed once, cut to its ends (`hagfish_scenario::echo`), in a message of
/// a few hundred bytes, and the refused run leaves no directory; `drag=[0.1, 0.2]` (a list
/// for a struct) is refused naming the struct's fields.
#[test]
fn a_huge_value_is_echoed_cut_and_a_list_for_a_struct_is_refused() {
    let dir = fresh_dir("overrides_huge");
    let out = dir.join("out");
    let huge = format!("duration_s=\"{}\"", "7".repeat(100_000));
    let output = run_form(&out, &["--set", &huge]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{}", stderr.len());
    assert!(stderr.len() < 1_000, "{} bytes: {}", stderr.len(), &stderr[..300]);
    assert!(stderr.contains("characters left out"), "{stderr}");
    assert!(!out.exists(), "a refused run made its directory");
    let output = run_form(&out, &["--set", "drag=[0.1, 0.2]"]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("`drag` is a struct with the fields linear_dyn_s_per_cm3"), "{stderr}");
}
