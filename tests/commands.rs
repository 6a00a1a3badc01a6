//! `hagfish params` and `hagfish knot`, end to end.

mod common;

use common::{ROOT, code_and_stderr, fresh_dir, run_hagfish};

#[test]
fn params_lists_every_top_level_field_with_unit_and_default() {
    let output = run_hagfish(["params"]);
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).expect("UTF-8");
    let row = |name: &str| {
        text.lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("no row {name} in\n{text}"))
            .to_owned()
    };
    for name in ["name", "body", "time_step_s", "duration_s", "drag", "phases"] {
        row(name);
    }
    let record = row("record_every_s");
    assert!(record.split_whitespace().take(3).eq(["record_every_s", "s", "0.1"]), "{record}");
    assert!(row("Form.steps[].Move.speed").contains("cm/s"));
}

#[test]
fn knot_reads_a_centreline_and_reports_positioned_errors() {
    let dir = fresh_dir("knot_command");
    let out = dir.join("run");
    let run = run_hagfish([
        "run".as_ref(),
        format!("{ROOT}/tests/data/form.ron").as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(run.status.success(), "{}", code_and_stderr(&run).1);
    let centreline = out.join("centreline.csv");
    let output = run_hagfish(["knot".as_ref(), centreline.as_os_str()]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let text = String::from_utf8(output.stdout).expect("UTF-8");
    let rows: Vec<&str> = text.lines().skip(1).collect();
    assert_eq!(rows.len(), 16, "{text}");
    assert!(rows.iter().all(|r| r.split_whitespace().nth(2) == Some("0_1")), "{text}");

    let mut broken = std::fs::read_to_string(&centreline).expect("centreline.csv");
    broken = broken.replacen("\n0,0.0000,3,", "\n0,0.0000,3,abc", 1);
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, broken).expect("write");
    let output = run_hagfish(["knot".as_ref(), bad.as_os_str()]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2));
    let expected = format!(
        "error: {}:5:12: `x_cm` = \"abc1.484000\": expected a finite number",
        bad.display()
    );
    assert!(stderr.starts_with(&expected), "expected {expected}, got {stderr}");
}
