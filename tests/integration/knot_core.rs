//! The knotted core in `metrics.csv`: on the forming run, once the trefoil is tied, every
//! frame names its core, whose columns agree with each other and with the knot analysis'
//! own midpoint (`knot_position_cm`), and whose length in diameters is that of a real knot
//! (more than the ≈ 10 D that no trefoil in a tube can be tied in, less than the body).

use crate::common::{ROOT, code_and_stderr, fresh_dir, metrics_table, run_hagfish};

/// ES103's body length L (cm).
const BODY_LENGTH_CM: f64 = 42.4;

#[test]
fn the_knotted_core_is_reported_in_body_relative_units() {
    let dir = fresh_dir("knot_core");
    let scenario = format!("{ROOT}/data/scenarios/form.ron");
    let output = run_hagfish(["run", &scenario, "--quiet", "--out", &dir.to_string_lossy()]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let (index, rows) = metrics_table(&dir);
    let mut knotted = 0;
    for row in &rows {
        let value = |name: &str| row[index[name]].parse::<f64>().ok();
        if row[index["knot"]] != "3_1" {
            continue;
        }
        knotted += 1;
        let (start, end) =
            (value("knot_core_start_cm").expect("start"), value("knot_core_end_cm").expect("end"));
        let length = value("knot_core_length_cm").expect("length");
        assert!((length - (end - start)).abs() < 2e-3, "frame {}", row[0]);
        let position = value("knot_position_cm").expect("the analysis' midpoint");
        assert!((position - 0.5 * (start + end)).abs() < 2e-3, "frame {}", row[0]);
        let mid = value("knot_core_mid_L").expect("mid");
        assert!((mid * BODY_LENGTH_CM - position).abs() < 5e-3, "frame {}", row[0]);
        let fraction = value("knot_core_length_L").expect("length / L");
        assert!((fraction * BODY_LENGTH_CM - length).abs() < 5e-3, "frame {}", row[0]);
        let diameters = value("knot_core_length_D").expect("length / D");
        assert!((10.0..24.0).contains(&diameters), "frame {}: {diameters} D", row[0]);
        assert!(start >= 0.0 && end <= BODY_LENGTH_CM, "frame {}", row[0]);
    }
    assert!(knotted >= 50, "the trefoil is held on {knotted} frames only");
    let unknotted = rows.iter().find(|r| r[index["knot"]] == "0_1").expect("frame 0 is unknotted");
    assert_eq!(unknotted[index["knot_core_start_cm"]], "");
}
