//! `hagfish modes` on a real run: the thesis scenario (tie, tighten, slide on ES103) with its
//! report's modes section, then
//! the decomposition of its slide, the slide against itself (`--against`), and the errors of
//! a missing run, an unknown phase, a phase without force and a selection that mixes kinds.

use crate::common::{ROOT, code_and_stderr, fresh_dir, run_hagfish};

#[test]
fn modes_of_the_thesis_slide_and_clear_errors() {
    let dir = fresh_dir("modes-thesis");
    let run = dir.join("run");
    let scenario = format!("{ROOT}/data/scenarios/thesis.ron");
    let made = run_hagfish(["run", scenario.as_str(), "--out", run.to_str().expect("utf-8")]);
    assert!(made.status.success(), "{}", code_and_stderr(&made).1);
    // The report's modes section: a table for each thigmotaxis phase and the shapes.
    let html = std::fs::read_to_string(run.join("report.html")).expect("report.html");
    let section = html.split_once("<section id=\"modes\">").expect("a modes section").1;
    let section = section.split_once("</section>").expect("the section ends").0;
    assert!(section.contains("<h2>Modes of the force field</h2>"));
    for phase in ["tighten", "slide"] {
        assert!(section.contains(&format!("<h3>Phase {phase}</h3>")), "{phase}");
    }
    assert!(!section.contains("<h3>Phase tie</h3>"), "the tie has no thigmotaxic force");
    assert_eq!(section.matches("<tr><td>").count(), 2 * 5, "five selections per phase");
    assert_eq!(section.matches("<figure>").count(), 2 * 3, "bend-y, bend-z, twist shapes");
    assert!(section.contains("Mode shapes, phase slide, bend-y"));

    let output =
        run_hagfish(["modes".as_ref(), run.as_os_str(), "--phase".as_ref(), "slide".as_ref()]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("modes for 90 %"), "{stdout}");
    let modes = run.join("modes");
    for name in [
        "modes.csv",
        "time_courses.csv",
        "modes.json",
        "modes.npz",
        "energy_all.png",
        "shapes_bend-y.svg",
    ] {
        assert!(modes.join(name).is_file(), "{name} is written");
    }
    let json = json_file(&modes.join("modes.json"));
    let selections = json["selections"].as_array().expect("selections");
    assert_eq!(selections.len(), 5, "all, bend, bend-y, bend-z, twist");
    for s in selections {
        let energy: Vec<f64> = numbers(&s["energy_fractions"]);
        assert!((energy.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{energy:?}");
        let counts = ["0.90", "0.95", "0.99"].map(|l| s["modes_for"][l].as_u64().expect("a count"));
        assert!(counts[0] >= 1 && counts[0] <= counts[1] && counts[1] <= counts[2], "{counts:?}");
        assert!(s["wave"]["phase_speed_cm_s"].is_number(), "{s}");
    }
    let header = std::fs::read_to_string(modes.join("modes.csv")).expect("modes.csv");
    assert!(header.starts_with("kind,mode,axis,s_cm,s_L,shape\n"));

    let against = run_hagfish([
        "modes".as_ref(),
        run.as_os_str(),
        "--phase".as_ref(),
        "slide".as_ref(),
        "--against".as_ref(),
        run.as_os_str(),
    ]);
    assert!(against.status.success(), "{}", code_and_stderr(&against).1);
    let json = json_file(&modes.join("against.json"));
    let compared = json["selections"].as_array().expect("selections");
    assert_eq!(compared.len(), 3, "bend-y, bend-z, twist");
    for c in compared {
        let angles: Vec<f64> = numbers(&c["principal_angles_deg"]);
        assert_eq!(angles.len(), 8);
        assert!(angles.iter().all(|a| a.abs() < 1e-9), "a run against itself: {angles:?}");
        let own: Vec<f64> = numbers(&c["own_cumulative"]);
        let captured: Vec<f64> = numbers(&c["captured_by_other"]);
        assert_eq!(captured.len(), 8);
        for (o, k) in own.iter().zip(&captured) {
            assert!((o - k).abs() < 1e-12, "its own modes capture its cumulative energy");
        }
    }
    let mixed = run_hagfish([
        "modes".as_ref(),
        run.as_os_str(),
        "--against".as_ref(),
        run.as_os_str(),
        "--kind".as_ref(),
        "all".as_ref(),
    ]);
    let (code, stderr) = code_and_stderr(&mixed);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("one DOF kind"), "{stderr}");
    let no_other = run_hagfish([
        "modes".as_ref(),
        run.as_os_str(),
        "--against".as_ref(),
        dir.join("nothing").as_os_str(),
    ]);
    let (code, stderr) = code_and_stderr(&no_other);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("nothing") && stderr.contains("does not exist"), "{stderr}");

    let missing = run_hagfish(["modes".as_ref(), dir.join("nothing").as_os_str()]);
    let (code, stderr) = code_and_stderr(&missing);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("does not exist"), "{stderr}");
    let unknown =
        run_hagfish(["modes".as_ref(), run.as_os_str(), "--phase".as_ref(), "swim".as_ref()]);
    let (code, stderr) = code_and_stderr(&unknown);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("swim") && stderr.contains("slide"), "names the phases: {stderr}");
    let tie = run_hagfish(["modes".as_ref(), run.as_os_str(), "--phase".as_ref(), "tie".as_ref()]);
    let (code, stderr) = code_and_stderr(&tie);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("zero"), "no thigmotaxis force while tying: {stderr}");
}

/// A JSON file's value.
fn json_file(path: &std::path::Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).expect("a JSON file");
    serde_json::from_str(&text).expect("JSON")
}

/// A JSON array of numbers.
fn numbers(value: &serde_json::Value) -> Vec<f64> {
    serde_json::from_value(value.clone()).expect("an array of numbers")
}
