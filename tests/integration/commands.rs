//! `hagfish params` and `hagfish knot`, end to end.

use crate::common::{ROOT, code_and_stderr, fresh_dir, run_hagfish};

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
        "error: {}:5: field 4 `x_cm` (\"abc1.484000\") is not a finite number",
        bad.display()
    );
    assert!(stderr.starts_with(&expected), "expected {expected}, got {stderr}");
}

/// A centreline of `points` points `curve(i)` as one frame of a `centreline.csv`.
fn write_centreline(path: &std::path::Path, points: usize, curve: impl Fn(usize) -> [f64; 3]) {
    let mut text = String::from("frame,time_s,body,x_cm,y_cm,z_cm\n");
    for i in 0..points {
        let [x, y, z] = curve(i);
        text.push_str(&format!("0,0,{i},{x},{y},{z}\n"));
    }
    std::fs::write(path, text).expect("write centreline");
}

/// 100 000 points (the largest documented body count): a smooth trefoil gets its answer; a
/// random walk, whose projections show ~10⁵ crossings (an 838 GB determinant), gets an error
/// naming the limit instead of an abort — both within the test's time and memory.
#[test]
fn knot_answers_or_refuses_a_hundred_thousand_point_centreline() {
    let dir = fresh_dir("knot_large");
    let n = 100_000;
    let smooth = dir.join("trefoil.csv");
    write_centreline(&smooth, n, |i| {
        let t = std::f64::consts::TAU * i as f64 / n as f64;
        [t.sin() + 2.0 * (2.0 * t).sin(), t.cos() - 2.0 * (2.0 * t).cos(), -(3.0 * t).sin()]
    });
    let output = run_hagfish(["knot".as_ref(), smooth.as_os_str()]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let text = String::from_utf8(output.stdout).expect("UTF-8");
    assert_eq!(
        text.lines().nth(1).and_then(|r| r.split_whitespace().nth(2)),
        Some("3_1"),
        "{text}"
    );

    // A deterministic random walk (a 64-bit linear congruential generator, steps in [-1, 1)).
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        state =
            state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    let mut walk = Vec::with_capacity(n);
    let mut at = [0.0; 3];
    for _ in 0..n {
        for x in &mut at {
            *x += next();
        }
        walk.push(at);
    }
    let tangled = dir.join("walk.csv");
    write_centreline(&tangled, n, |i| walk[i]);
    let output = run_hagfish(["knot".as_ref(), tangled.as_os_str()]);
    let (code, stderr) = code_and_stderr(&output);
    assert!(!stderr.contains("panicked") && code == Some(0), "exit {code:?}: {stderr}");
    let text = String::from_utf8(output.stdout).expect("UTF-8");
    assert!(text.contains("too tangled") && text.contains("500 crossings"), "{text}");
}
