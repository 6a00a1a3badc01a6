//! The user-named fields that reach the outputs — the scenario's name and a thigmotaxis phase's
//! — as arbitrary text (commas, quotes, newlines, `<!--<script>`, U+2028, any Unicode): the run
//! completes and every output that carries a name reads it back unchanged: `metrics.csv`
//! through the `csv` crate, the report's embedded run data and `manifest.json` through
//! `serde_json` (with no `<` left in the report's script element to close or open another),
//! and the run's `scenario.ron` by loading it again.

use std::path::Path;

use hagfish_scenario::LoadedScenario;
use proptest::prelude::*;

use crate::common::{ROOT, fresh_dir, run_into};

/// `tests/data/form.ron` named `name` with one thigmotaxis phase named `name` too (0.1 s, on
/// the straight body: its name is what is tested, not its forces), written by `ron` (which
/// escapes the names).
fn scenario_named(dir: &Path, name: &str) -> std::path::PathBuf {
    let mut base = LoadedScenario::load(format!("{ROOT}/tests/data/form.ron")).expect("form.ron");
    base.scenario.name = name.to_owned();
    let mut text = ron::to_string(&base.scenario).expect("a scenario serialises");
    let phase = format!(
        "[Thigmotaxis((name: {}, parameters: (head: (v_a: 0.0, v_b: 0.0), tail: (v_a: 0.0, \
         v_b: 0.0), tail_pull_dyn: 0.0, max_force_dyn: 100.0), until: (seconds: 0.1)))]",
        ron::to_string(name).expect("a string serialises")
    );
    let start = text.find("phases:[").expect("the phases") + "phases:".len();
    let end = start + text[start..].find("],backend").expect("the end of the phases") + 1;
    text.replace_range(start..end, &phase);
    text = text.replacen("duration_s:1.5", "duration_s:0.3", 1);
    let path = dir.join("named.ron");
    std::fs::write(&path, text).expect("write the scenario");
    path
}

fn name_round_trips(name: &str) -> Result<(), TestCaseError> {
    let dir = fresh_dir("user_names");
    let scenario = scenario_named(&dir, name);
    let out = dir.join("run");
    let output = run_into(&scenario.to_string_lossy(), &out, &[]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    prop_assert_eq!(output.status.code(), Some(0), "{}", stderr);
    let mut metrics = csv::Reader::from_path(out.join("metrics.csv")).expect("metrics.csv");
    let column = metrics.headers().expect("a header").iter().position(|h| h == "phase");
    let column = column.expect("a phase column");
    let phases: Vec<String> =
        metrics.records().map(|r| r.expect("a record")[column].to_owned()).collect();
    prop_assert!(phases.iter().any(|p| p == name), "{:?} not among {:?}", name, phases);
    let html = std::fs::read_to_string(out.join("report.html")).expect("report.html");
    let open = r#"<script type="application/json" id="run-data">"#;
    let start = html.find(open).expect("the run data") + open.len();
    let data = &html[start..start + html[start..].find("</script>").expect("its end")];
    prop_assert!(!data.contains('<'), "a '<' in the run data");
    let value: serde_json::Value = serde_json::from_str(data).expect("the run data is JSON");
    let states = value["states"].as_array().expect("states");
    let wanted = format!("phase {name}, knot");
    prop_assert!(states.iter().filter_map(|s| s.as_str()).any(|s| s.starts_with(&wanted)));
    let manifest = std::fs::read_to_string(out.join("manifest.json")).expect("manifest.json");
    let manifest: serde_json::Value = serde_json::from_str(&manifest).expect("JSON");
    prop_assert_eq!(manifest["scenario_name"].as_str(), Some(name));
    let again = LoadedScenario::load(out.join("scenario.ron")).expect("the run's scenario.ron");
    prop_assert_eq!(again.scenario.name.as_str(), name);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Arbitrary names of 1–40 characters, with the characters that broke outputs before
    /// (`,`, `"`, newline, `<!--`, U+2028) mixed in.
    #[test]
    fn a_scenario_and_a_phase_name_reach_every_output_unchanged(
        name in "[,\"\n<>&!\u{2028}a-z]{1,8}[\\PC]{0,32}"
    ) {
        name_round_trips(&name)?;
    }
}
