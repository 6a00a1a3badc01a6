//! Exit codes and error messages of `hagfish run`: a malformed scenario is one `error:` line
//! naming file, line and column and what was expected, exit code 2; a diverging run keeps its
//! outputs, writes its checkpoint and the failing state, marks the manifest `diverged` and
//! exits with 3. Never a panic.

use crate::common::{self, ROOT, code_and_stderr, csv_rows, fresh_dir, manifest, run_hagfish};

/// Writes `tests/data/form.ron` with `edit` applied (and the body path made absolute) into a
/// fresh directory, runs it, and returns the exit code and stderr.
fn run_edited(name: &str, edit: impl Fn(&str) -> String) -> (Option<i32>, String, String) {
    let dir = fresh_dir(name);
    let text = std::fs::read_to_string(format!("{ROOT}/tests/data/form.ron")).expect("form.ron");
    let text =
        text.replace("../../data/hagfish/es103.ron", &format!("{ROOT}/data/hagfish/es103.ron"));
    let scenario = dir.join("scenario.ron");
    std::fs::write(&scenario, edit(&text)).expect("write the scenario");
    let output = run_hagfish([
        "run".as_ref(),
        scenario.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        dir.join("out").as_os_str(),
    ]);
    let (code, stderr) = code_and_stderr(&output);
    (code, stderr, scenario.display().to_string())
}

/// Asserts exit code 2 and exactly one line `error: FILE:LINE:COLUMN: MESSAGE…`.
fn assert_user_error(name: &str, edit: impl Fn(&str) -> String, position: &str, message: &str) {
    let (code, stderr, file) = run_edited(name, edit);
    assert_eq!(code, Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let expected = format!("error: {file}:{position}: {message}");
    assert!(stderr.starts_with(&expected), "expected `{expected}`, got `{stderr}`");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// One test a case: `name`'s output directory is `error_name`, `from => to` the edit of
/// form.ron, then the expected `LINE:COLUMN` and the start of the message (see
/// [`assert_user_error`]).
macro_rules! user_error {
    ($name:ident, $from:expr => $to:expr, $position:expr, $message:expr) => {
        #[test]
        fn $name() {
            let name = concat!("error_", stringify!($name));
            assert_user_error(name, |t| t.replace($from, $to), $position, $message);
        }
    };
}

user_error!(syntax_error, "duration_s: 1.5," => "duration_s: 1.5", "8:5", "Expected comma");
user_error!(unknown_field, "record_every_s" => "record_evry_s", "8:5",
    "unknown field `record_evry_s`, expected one of: name, body, time_step_s, duration_s, end_after_phases, record_every_s, observe_every_s, drag, initial_shape, skin, phases, backend, acceptance");
user_error!(wrong_type, "time_step_s: 0.01" => "time_step_s: \"fast\"", "6:17", "Expected float");
user_error!(negative_time_step, "time_step_s: 0.01" => "time_step_s: -0.01", "6:18",
    "time_step_s = -0.01 is out of range: expected finite and ≥ 1e-6");
user_error!(time_step_below_the_floor, "time_step_s: 0.01" => "time_step_s: 1e-300", "6:18",
    "time_step_s = 1e-300 is out of range: expected finite and ≥ 1e-6");
user_error!(unknown_phase, "Hold(0.5)" => "Wait(0.5)", "18:9",
    "Unexpected variant named `Wait` in enum `Phase`, expected one of `Form`, `Hold`, `Thigmotaxis`, `Tie`, `Load`, `Follow`, or `Pull` instead");
user_error!(
    an_initial_knot_that_is_no_torus_knot_is_located_at_its_value,
    "    phases: [" => "    initial_shape: Some(OpenTorusKnot((crossings: 4, radius_l: 0.02, start_l: \
                       0.1))),\n    phases: [",
    "10:51",
    "crossings = 4 is out of range: expected an odd number ≥ 3"
);
user_error!(missing_body_file, "es103.ron" => "missing.ron", "5:11",
    &format!("body: {ROOT}/data/hagfish/missing.ron: cannot read the file"));

#[test]
fn too_many_steps_are_refused_before_the_run_starts() {
    let (code, stderr, _) =
        run_edited("error_too_many_steps", |t| t.replace("duration_s: 1.5", "duration_s: 1e9"));
    assert_eq!(code, Some(2), "{stderr}");
    assert_eq!(
        stderr.trim(),
        "error: the scenario needs 1e11 steps (duration_s / time_step_s), more than the cap of \
         100000000: shorten it, raise the time step, or allow more with --max-steps"
    );
}

#[test]
fn missing_scenario_file() {
    let dir = fresh_dir("error_missing_scenario");
    let missing = dir.join("none.ron");
    let output =
        run_hagfish(["run".as_ref(), missing.as_os_str(), "--out".as_ref(), dir.as_os_str()]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.starts_with(&format!("error: {}: cannot read the file", missing.display())),
        "{stderr}"
    );
}

#[test]
fn a_diverging_run_keeps_its_outputs_and_exits_with_3() {
    let dir = fresh_dir("error_diverge");
    let output = run_hagfish([
        "run".as_ref(),
        format!("{ROOT}/tests/data/diverge.ron").as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        dir.as_os_str(),
    ]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(3), "{stderr}");
    assert!(stderr.starts_with("error: the run diverged: step 35 (t = 0.35"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let manifest = manifest(&dir);
    assert_eq!(manifest["status"], "diverged");
    assert_eq!(manifest["frames"], 4);
    assert!(manifest["error"].as_str().is_some_and(|e| e.contains("not positive definite")));
    let metrics = csv_rows(&dir.join("metrics.csv"));
    assert_eq!(common::frames_of(&metrics), [0, 1, 2, 3]);
    for file in ["checkpoint.ron", "diverged.ron"] {
        let text = std::fs::read_to_string(dir.join(file)).expect(file);
        assert!(text.contains("steps: "), "{file}: {text}");
    }
    let diverged = std::fs::read_to_string(dir.join("diverged.ron")).expect("diverged.ron");
    assert!(diverged.contains("steps: 35,"));
    let checkpoint = std::fs::read_to_string(dir.join("checkpoint.ron")).expect("checkpoint.ron");
    assert!(checkpoint.contains("steps: 30,") && checkpoint.contains("frames: 4,"));

    // Resumed from its last frame, the run fails again at the same step.
    let again = run_hagfish(["run".as_ref(), "--resume".as_ref(), dir.as_os_str()]);
    let (code, stderr) = code_and_stderr(&again);
    assert_eq!(code, Some(3), "{stderr}");
    assert!(stderr.starts_with("error: the run diverged: step 35 (t = 0.35"), "{stderr}");
    assert_eq!(common::manifest(&dir)["resumed_at_frames"], serde_json::json!([4]));
}

#[test]
fn out_of_range_phase_values_are_located_at_their_occurrence() {
    // The second `Hold(` of the file (a phase, after the script's own Hold step).
    assert_user_error(
        "error_negative_hold",
        |t| t.replace("Hold(0.5)", "Hold(-0.5)"),
        "18:14",
        "Hold = -0.5 is out of range: expected finite and ≥ 0",
    );
    // A body index past the tail; the scenario's own `body:` (the file) is not mistaken for it.
    assert_user_error(
        "error_body_index",
        |t| t.replace("Point((30.0, 20.0, 0.0))", "FromBody(body: 100, offset: (0.0, 0.0, 0.0))"),
        "14:41",
        "body = 100 is out of range: expected a body index below 100 (0 = head)",
    );
    // A tie asking for more tube tail-ward of its crossover than the whole body has.
    assert_user_error(
        "error_min_tail_d",
        |t| t.replace("Hold(0.5)", "Tie((knot: FigureEight, at: 0.31, min_tail_d: Some(30.0)))"),
        "18:55",
        "min_tail_d = 30 is out of range: expected > 0 and less than the body's length, 26.0 \
         local diameters",
    );
    assert_user_error(
        "error_zero_speed",
        |t| t.replace("speed: 5.0", "speed: 0.0"),
        "14:59",
        "speed = 0 is out of range: expected finite and > 0",
    );
}

/// A phase end condition whose quantity cannot be read in its unit is refused as the file is
/// read, at the end of the condition (ron's position: its closing parenthesis).
#[test]
fn an_end_condition_in_a_unit_its_quantity_has_not_is_refused() {
    let load = "Load((force_dyn: 0.0, direction: TailTangent, \
                until: (seconds: 0.5, when: [(KineticEnergy, Below, Cm(1.0))])))";
    assert_user_error(
        "error_condition_unit",
        |t| t.replace("Hold(0.5)", load),
        "18:114",
        "(KineticEnergy, Below, Cm(…)) is not an end condition: KineticEnergy is compared \
         Below, in Erg",
    );
}
