//! End to end: `hagfish run data/scenarios/form.ron --out DIR` (the README's main job) writes
//! parseable outputs, and its knot forms and holds: a trefoil with agreement ≥ 0.9 in every
//! frame of the last 2 s, penetration below 2 % of the radius, joint limits within 0.5°.

use std::path::PathBuf;
use std::process::Command;

/// Runs `hagfish run data/scenarios/form.ron --quiet` into a fresh directory named `name`
/// under the test target's temporary directory and returns that directory.
fn run_form(name: &str) -> PathBuf {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    let scenario = concat!(env!("CARGO_MANIFEST_DIR"), "/data/scenarios/form.ron");
    let output = Command::new(env!("CARGO_BIN_EXE_hagfish"))
        .args(["run", scenario, "--quiet", "--out"])
        .arg(&out)
        .output()
        .expect("hagfish runs");
    assert!(output.status.success(), "exit status {}", output.status);
    let summary = String::from_utf8_lossy(&output.stdout);
    assert!(!summary.contains("dense backend"), "no backend hint at 100 bodies: {summary}");
    out
}

#[test]
fn form_scenario_ties_and_holds_a_trefoil() {
    let out = run_form("run_form");

    let metrics = std::fs::read_to_string(out.join("metrics.csv")).expect("metrics.csv");
    let mut lines = metrics.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let (time, knot, agreement) = (column("time_s"), column("knot"), column("knot_agreement"));
    let (penetration, limits) =
        (column("max_self_penetration_rel"), column("max_limit_excess_deg"));
    let rows: Vec<Vec<String>> = lines.map(|l| l.split(',').map(str::to_owned).collect()).collect();
    assert_eq!(rows.len(), 301, "frames every 0.1 s over 30 s, and frame 0");
    let number = |row: &Vec<String>, i: usize| row[i].parse::<f64>().expect("a number");
    for row in rows.iter().filter(|r| number(r, time) >= 28.0) {
        assert_eq!(row[knot], "3_1", "at t = {}", row[time]);
        assert!(number(row, agreement) >= 0.9, "agreement {} at t = {}", row[agreement], row[time]);
    }
    let worst = |i: usize| rows.iter().map(|r| number(r, i)).fold(0.0, f64::max);
    assert!(worst(penetration) < 0.02, "penetration {} of the radius", worst(penetration));
    assert!(worst(limits) < 0.5, "limit excess {}°", worst(limits));

    let centreline = std::fs::read_to_string(out.join("centreline.csv")).expect("centreline.csv");
    assert_eq!(centreline.lines().next(), Some("frame,time_s,body,x_cm,y_cm,z_cm"));
    assert_eq!(centreline.lines().count(), 1 + 301 * 100);
}

#[test]
fn the_same_scenario_gives_bit_identical_outputs() {
    let (first, second) = (run_form("determinism_a"), run_form("determinism_b"));
    for file in ["centreline.csv", "metrics.csv", "forces.csv"] {
        let a = std::fs::read(first.join(file)).expect(file);
        let b = std::fs::read(second.join(file)).expect(file);
        assert!(!a.is_empty() && a == b, "{file} differs between two runs");
    }
}
