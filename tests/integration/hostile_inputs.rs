//! Inputs that would read or write outside their place (issue 39, items 5 and 7): a sweep
//! plan whose run id leaves `runs/`, a device where a file is expected (`--body /dev/zero`,
//! `hagfish knot /dev/zero`, a grid value), and a scenario file that starts with a byte order
//! mark (accepted).

use std::path::Path;

use crate::common::{ROOT, code_and_stderr, fresh_dir, manifest, run_hagfish};

/// A one-run sweep of the short forming scenario, planned in `folder`.
fn planned_sweep(dir: &Path, folder: &Path) {
    let grid = dir.join("grid.ron");
    let text = format!(
        "Sweep(scenario: \"{ROOT}/tests/data/form.ron\", grid: [(\"duration_s\", [\"0.2\"])])"
    );
    std::fs::write(&grid, text).expect("grid");
    let output = run_hagfish([
        "sweep".as_ref(),
        "plan".as_ref(),
        grid.as_os_str(),
        "--out".as_ref(),
        folder.as_os_str(),
    ]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
}

#[test]
fn a_plan_whose_run_id_leaves_its_folder_is_refused() {
    let dir = fresh_dir("hostile_plan_ids");
    let folder = dir.join("sweep");
    planned_sweep(&dir, &folder);
    let plan_path = folder.join("plan.json");
    let planned: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&plan_path).expect("plan")).expect("JSON");
    let victim = dir.join("victim");
    let absolute = victim.to_string_lossy().into_owned();
    for id in ["../../victim", absolute.as_str(), "a/b", "..", ""] {
        let mut plan = planned.clone();
        plan["runs"][0]["id"] = id.into();
        std::fs::write(&plan_path, plan.to_string()).expect("write the plan");
        let output = run_hagfish(["sweep", "run", &folder.to_string_lossy()]);
        let (code, stderr) = code_and_stderr(&output);
        assert_eq!(code, Some(2), "{id}: {stderr}");
        assert!(stderr.contains("run id"), "{id}: {stderr}");
        assert!(!victim.exists(), "{id}: a run was written outside the sweep");
        assert!(!folder.join("runs/a").exists(), "{id}");
    }
    // The plan as made still runs.
    std::fs::write(&plan_path, planned.to_string()).expect("write the plan");
    let output = run_hagfish(["sweep", "run", &folder.to_string_lossy()]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
}

#[test]
fn a_device_where_a_file_is_expected_is_refused_at_once() {
    let dir = fresh_dir("hostile_devices");
    let out = dir.join("out");
    let scenario = format!("{ROOT}/tests/data/form.ron");
    let out_arg = out.to_string_lossy().into_owned();
    let body = ["run", &scenario, "--quiet", "--out", &out_arg, "--body", "/dev/zero"];
    for args in [&body[..], &["knot", "/dev/zero"][..]] {
        let output = run_hagfish(args);
        let (code, stderr) = code_and_stderr(&output);
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("/dev/zero") && stderr.contains("not a regular file"), "{stderr}");
    }
    assert!(!out.exists(), "a refused run made its directory");
    let grid = dir.join("grid.ron");
    let text =
        format!("Sweep(scenario: \"{scenario}\", grid: [(\"body\", [\"\\\"/dev/zero\\\"\"])])");
    std::fs::write(&grid, text).expect("grid");
    let folder = dir.join("sweep").to_string_lossy().into_owned();
    let output = run_hagfish(["sweep", "plan", &grid.to_string_lossy(), "--out", &folder]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("not a regular file"), "{stderr}");
}

#[test]
fn a_scenario_file_with_a_byte_order_mark_runs() {
    let dir = fresh_dir("hostile_bom");
    let text = std::fs::read_to_string(format!("{ROOT}/tests/data/form.ron")).expect("form.ron");
    let body = format!("\"{ROOT}/data/hagfish/es103.ron\"");
    let text = text.replace("\"../../data/hagfish/es103.ron\"", &body);
    let scenario = dir.join("bom.ron");
    std::fs::write(&scenario, format!("\u{feff}{text}")).expect("write");
    let out = dir.join("out");
    let output = run_hagfish([
        "run".as_ref(),
        scenario.as_os_str(),
        "--quiet".as_ref(),
        "--stop-after-frames".as_ref(),
        "0".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert_eq!(manifest(&out)["scenario_name"], "form-short");
}
