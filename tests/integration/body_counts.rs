//! The thesis scenario on bodies of other sizes (issue 16, scale limits): every index rule is
//! body-relative, so 200 and 1000 bodies start and run its first second; a body too large for
//! the machine's memory is refused with exit 2 before anything large is allocated. On the
//! sparse backend (the default) they run as they are; on the dense one the summary of such a
//! run names the sparse backend.

use std::path::{Path, PathBuf};

use crate::common::{ROOT, code_and_stderr, csv_rows, fresh_dir, manifest, run_hagfish};

/// `thesis.ron` cut to `duration_s`, on ES103 made of `bodies` bodies, written into `dir`.
fn thesis_with_bodies(dir: &Path, bodies: usize, duration_s: f64) -> PathBuf {
    let body = std::fs::read_to_string(format!("{ROOT}/data/hagfish/es103.ron")).expect("es103");
    let body = body.replace(" body_count: 100,", &format!(" body_count: {bodies},"));
    let body_path = dir.join(format!("es103_{bodies}.ron"));
    std::fs::write(&body_path, body).expect("write body");
    let scenario =
        std::fs::read_to_string(format!("{ROOT}/data/scenarios/thesis.ron")).expect("thesis");
    let duration = line_starting(&scenario, "    duration_s: ");
    let scenario = scenario
        .replace("\"../hagfish/es103.ron\"", &format!("{:?}", body_path.display().to_string()))
        .replace(&duration, &format!("    duration_s: {duration_s:?},"));
    let path = dir.join(format!("thesis_{bodies}.ron"));
    std::fs::write(&path, scenario).expect("write scenario");
    path
}

/// The whole line of `text` that starts with `start`.
fn line_starting(text: &str, start: &str) -> String {
    text.lines().find(|l| l.starts_with(start)).unwrap_or_else(|| panic!("no {start:?}")).to_owned()
}

/// Runs the thesis scenario's first `duration_s` on `bodies` bodies with the `--set`
/// arguments `sets` and checks that it completes with every frame recorded and the wall and
/// joint limits respected; returns its summary.
fn runs_first_second(bodies: usize, duration_s: f64, sets: &[&str]) -> String {
    let dir = fresh_dir(&format!("bodies_{bodies}"));
    let scenario = thesis_with_bodies(&dir, bodies, duration_s);
    let out = dir.join("run");
    let mut args = vec![
        "run".as_ref(),
        scenario.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ];
    args.extend(sets.iter().flat_map(|set| ["--set".as_ref(), std::ffi::OsStr::new(set)]));
    let output = run_hagfish(args);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(0), "{bodies} bodies: {stderr}");
    assert_eq!(manifest(&out)["status"], "completed");
    let rows = csv_rows(&out.join("centreline.csv"));
    let frames = (duration_s / 0.1).round() as usize + 1;
    assert_eq!(rows.len(), frames * bodies, "{bodies} bodies: every body of every frame");
    let summary = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(summary.contains("max wall penetration 0.0000 cm"), "{summary}");
    summary
}

/// On the dense backend, chosen, the summary names the sparse one.
#[test]
fn two_hundred_bodies_run_the_thesis_scenario() {
    let summary = runs_first_second(200, 1.0, &["backend=DenseReduced"]);
    let hint = "200 bodies on the dense backend";
    assert!(summary.contains(hint), "the summary names the sparse backend: {summary}");
}

/// On the default (sparse) backend the summary has no backend hint.
#[test]
fn a_thousand_bodies_run_the_thesis_scenario() {
    let summary = runs_first_second(1000, 0.5, &[]);
    assert!(!summary.contains("dense backend"), "{summary}");
}

/// 100 000 bodies (the largest count a biometrics file may give) need ≈ 3.6 TB of step
/// buffers on the dense backend: refused with exit 2 and the estimate, in well under a second
/// of model building. (The sparse backend needs memory linear in the bodies.)
#[test]
fn a_body_too_large_for_the_memory_is_refused_with_its_estimate() {
    let dir = fresh_dir("bodies_100000");
    let scenario = thesis_with_bodies(&dir, 100_000, 1.0);
    let out = dir.join("run");
    let output = run_hagfish([
        "run".as_ref(),
        scenario.as_os_str(),
        "--set".as_ref(),
        "backend=DenseReduced".as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.starts_with("error: a body of 100000 bodies (150000 DOFs) needs about"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}
