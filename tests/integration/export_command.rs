//! `hagfish export wcon DIR`: the midline of a run as WCON JSON whose points are the run's
//! body centres (x, y, and z under `@hagfish`), with units; a directory without a run is
//! refused (exit 2).

use crate::common::{ROOT, code_and_stderr, csv_rows, fresh_dir, run_hagfish};

#[test]
fn the_wcon_midline_is_the_runs_centreline_with_units() {
    let dir = fresh_dir("export_wcon");
    let run = dir.join("run");
    let scenario = format!("{ROOT}/data/scenarios/form.ron");
    let args = ["run", &scenario, "--out", run.to_str().expect("UTF-8"), "--quiet"];
    let output = run_hagfish(args.iter().chain(&["--set", "duration_s=1"]));
    assert_eq!(output.status.code(), Some(0), "{}", code_and_stderr(&output).1);
    let output = run_hagfish(["export", "wcon", run.to_str().expect("UTF-8")]);
    assert_eq!(output.status.code(), Some(0), "{}", code_and_stderr(&output).1);

    let text = std::fs::read_to_string(run.join("midline.wcon")).expect("midline.wcon");
    let wcon: serde_json::Value = serde_json::from_str(&text).expect("WCON is JSON");
    assert_eq!(wcon["units"], serde_json::json!({"t": "s", "x": "cm", "y": "cm", "z": "cm"}));
    let data = &wcon["data"][0];
    assert_eq!(data["id"], "1");
    let rows = csv_rows(&run.join("centreline.csv"));
    let times = data["t"].as_array().expect("arrayed t");
    assert_eq!(times.len() * 100, rows.len(), "a frame of 100 bodies per time");
    for row in rows.iter().step_by(37) {
        let (frame, body): (usize, usize) =
            (row[0].parse().expect("frame"), row[2].parse().expect("body"));
        for (axis, column) in [(&data["x"], 3), (&data["y"], 4), (&data["@hagfish"]["z"], 5)] {
            let value = axis[frame][body].as_f64().expect("a number");
            assert_eq!(value, row[column].parse::<f64>().expect("cm"), "frame {frame} body {body}");
        }
    }

    let output = run_hagfish(["export", "wcon", dir.to_str().expect("UTF-8")]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("centreline.csv"), "{stderr}");
}
