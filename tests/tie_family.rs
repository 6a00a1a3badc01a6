//! The tie controller on a family of bodies and time steps, without retuning
//! (`data/scenarios/tie.ron` as shipped, issue #14): length 35 and 50 cm (mass ∝ length),
//! circumferences ±15 %, stiffness ×0.1 and ×10, damping ×10, 50 and 300 bodies, the tail
//! taper, h = 0.005 and 0.02 s, drag ×0.5 and ×2, and ES103 in both handednesses. In each,
//! the trefoil of the asked handedness (sign of the core's writhe) is tied, holds on every
//! frame after, with its core's head-ward end at least 0.35 L from the head, self
//! penetration below 2 % of the local radius and no joint beyond its limit by 0.5°. And a
//! tie stopped mid-plan resumes bit for bit.

mod common;

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use common::{ROOT, code_and_stderr, fresh_dir, metrics_table, run_hagfish};

/// ES103's biometrics file with `edits` (text replacements) applied, written into `dir`.
fn body(dir: &Path, name: &str, edits: &[(&str, String)]) -> PathBuf {
    let mut text =
        std::fs::read_to_string(format!("{ROOT}/data/hagfish/es103.ron")).expect("es103.ron");
    for (from, to) in edits {
        assert!(text.contains(from), "{from} is in es103.ron");
        text = text.replace(from, to);
    }
    let path = dir.join(format!("{name}.ron"));
    std::fs::write(&path, text).expect("write a body");
    path
}

/// One member of the family: a name, body edits, `--set` overrides and the handedness.
struct Variant {
    name: &'static str,
    edits: Vec<(&'static str, String)>,
    sets: Vec<&'static str>,
    right_handed: bool,
}

fn variant(
    name: &'static str,
    edits: Vec<(&'static str, String)>,
    sets: Vec<&'static str>,
) -> Variant {
    Variant { name, edits, sets, right_handed: true }
}

fn family() -> Vec<Variant> {
    let length = |l: f64| {
        vec![
            ("length_cm: 42.4", format!("length_cm: {l}")),
            ("mass_g: 80.0", format!("mass_g: {}", 80.0 * l / 42.4)),
        ]
    };
    let circumference = |k: f64| {
        let c: Vec<String> = [5.6, 5.5, 5.6, 4.3].iter().map(|c| format!("{:.3}", c * k)).collect();
        vec![(
            "circumferences_cm: [5.6, 5.5, 5.6, 4.3]",
            format!("circumferences_cm: [{}]", c.join(", ")),
        )]
    };
    let stiffness = |k: f64| {
        vec![
            (
                "bending_stiffness_dyn_cm_per_rad: 1.0",
                format!("bending_stiffness_dyn_cm_per_rad: {k}"),
            ),
            (
                "twist_stiffness_dyn_cm_per_rad: 5.0",
                format!("twist_stiffness_dyn_cm_per_rad: {}", 5.0 * k),
            ),
        ]
    };
    vec![
        variant("es103", vec![], vec![]),
        Variant {
            right_handed: false,
            ..variant("es103_left", vec![], vec!["phases[0].Tie.knot=Trefoil(Left)"])
        },
        variant("length_35", length(35.0), vec![]),
        variant("length_50", length(50.0), vec![]),
        variant("circumference_0.85", circumference(0.85), vec![]),
        variant("circumference_1.15", circumference(1.15), vec![]),
        variant("stiffness_0.1", stiffness(0.1), vec![]),
        variant("stiffness_10", stiffness(10.0), vec![]),
        variant(
            "damping_10",
            vec![("damping_dyn_cm_s_per_rad: 0.1", "damping_dyn_cm_s_per_rad: 1.0".into())],
            vec![],
        ),
        variant("bodies_50", vec![("body_count: 100", "body_count: 50".into())], vec![]),
        variant("bodies_300", vec![("body_count: 100", "body_count: 300".into())], vec![]),
        variant(
            "taper",
            vec![("tail_taper: None", "tail_taper: Some((tip_radius_cm: 0.3))".into())],
            vec![],
        ),
        variant("h_0.005", vec![], vec!["time_step_s=0.005"]),
        variant("h_0.02", vec![], vec!["time_step_s=0.02"]),
        variant("drag_0.5", vec![], vec!["drag.quadratic_g_per_cm3=0.25"]),
        variant("drag_2", vec![], vec!["drag.quadratic_g_per_cm3=1.0"]),
    ]
}

/// Runs `variant` of tie.ron into `dir` and checks it; returns a failure message, if any.
fn check(dir: &Path, variant: &Variant) -> Option<String> {
    let body = body(dir, variant.name, &variant.edits);
    let out = dir.join(format!("run_{}", variant.name));
    let (scenario, out_text) = (format!("{ROOT}/data/scenarios/tie.ron"), out.to_string_lossy());
    let mut args = vec!["run", &scenario, "--quiet", "--out", &out_text, "--body"];
    let body_text = body.to_string_lossy();
    args.push(&body_text);
    for set in &variant.sets {
        args.extend(["--set", set]);
    }
    let output = run_hagfish(&args);
    if !output.status.success() {
        return Some(format!("{}: {}", variant.name, code_and_stderr(&output).1));
    }
    let (header, rows) = metrics_table(&out);
    let number = |row: &[String], name: &str| row[header[name]].parse::<f64>().unwrap_or(f64::NAN);
    let Some(tied) = rows.iter().position(|r| r[header["phase"]] != "tie") else {
        return Some(format!("{}: not tied in {} frames", variant.name, rows.len()));
    };
    let after = &rows[tied..];
    let sign = if variant.right_handed { 1.0 } else { -1.0 };
    let held = after
        .iter()
        .filter(|r| r[header["knot"]] == "3_1" && sign * number(r, "knot_writhe") > 0.5)
        .count();
    let penetration =
        rows.iter().map(|r| number(r, "max_self_penetration_rel")).fold(0.0, f64::max);
    let limit = rows.iter().map(|r| number(r, "max_limit_excess_deg")).fold(0.0, f64::max);
    let core_start = number(&rows[tied], "knot_core_start_L");
    let failures = [
        (
            held as f64 >= 0.99 * after.len() as f64,
            format!("held on {held} of {} frames", after.len()),
        ),
        (penetration < 0.02, format!("self penetration {:.2} % of r", 100.0 * penetration)),
        (limit < 0.5, format!("limit excess {limit}°")),
        (core_start >= 0.35, format!("core's head-ward end at {core_start} L when tied")),
    ];
    let failed: Vec<String> = failures.into_iter().filter(|(ok, _)| !ok).map(|(_, m)| m).collect();
    (!failed.is_empty()).then(|| format!("{}: {}", variant.name, failed.join("; ")))
}

#[test]
fn the_trefoil_is_tied_and_held_on_every_member_of_the_family() {
    let dir = fresh_dir("tie_family");
    let family = family();
    let next = Mutex::new(family.iter());
    let failures = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..2 {
            scope.spawn(|| {
                loop {
                    let Some(variant) = next.lock().expect("the queue").next() else { break };
                    if let Some(failure) = check(&dir, variant) {
                        failures.lock().expect("the failures").push(failure);
                    }
                }
            });
        }
    });
    let failures = failures.into_inner().expect("the failures");
    assert!(
        failures.is_empty(),
        "{} of {} failed:\n{}",
        failures.len(),
        family.len(),
        failures.join("\n")
    );
}

#[test]
fn a_tie_stopped_mid_plan_resumes_bit_for_bit() {
    let dir = fresh_dir("tie_resume");
    let scenario = format!("{ROOT}/data/scenarios/tie.ron");
    let (straight, stopped) = (dir.join("straight"), dir.join("stopped"));
    let output = run_hagfish(["run", &scenario, "--quiet", "--out", &straight.to_string_lossy()]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    // Frame 160 (16 s) is after the plan's insertion and before the knot has held 0.5 s.
    let stop = [
        "run",
        &scenario,
        "--quiet",
        "--out",
        &stopped.to_string_lossy(),
        "--stop-after-frames",
        "160",
    ];
    assert!(run_hagfish(stop).status.success());
    let resumed = run_hagfish(["run", "--resume", &stopped.to_string_lossy(), "--quiet"]);
    assert!(resumed.status.success(), "{}", code_and_stderr(&resumed).1);
    for file in ["q.npy", "qdot.npy", "metrics.csv"] {
        let a = std::fs::read(straight.join(file)).expect(file);
        let b = std::fs::read(stopped.join(file)).expect(file);
        assert!(a == b, "{file} differs after the resume");
    }
}

/// The slide of `tie_slide.ron` with `extra` arguments: the core midpoint's travel toward
/// the head (L) from the slide's start, the core's nearest head-ward end (L), its length
/// change (fraction) and the midpoint's speed over the middle 80 % of the slide (cm/s).
fn slide(name: &str, extra: &[&str]) -> (f64, f64, f64, f64) {
    let dir = fresh_dir(name);
    let scenario = format!("{ROOT}/data/scenarios/tie_slide.ron");
    let out = dir.to_string_lossy();
    let mut args = vec!["run", &scenario, "--quiet", "--out", &out];
    args.extend_from_slice(extra);
    let output = run_hagfish(&args);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let (header, rows) = metrics_table(&dir);
    let number = |row: &[String], name: &str| row[header[name]].parse::<f64>().unwrap_or(f64::NAN);
    let slide: Vec<&Vec<String>> = rows.iter().filter(|r| r[header["phase"]] == "slide").collect();
    assert!(slide.len() >= 10, "{} slide frames", slide.len());
    let tied = rows.iter().position(|r| r[header["phase"]] != "tie").expect("tied");
    assert!(rows[tied..].iter().all(|r| r[header["knot"]] == "3_1"), "the trefoil is lost");
    let (first, last) = (slide[0], slide[slide.len() - 1]);
    let mid = |r: &Vec<String>| number(r, "knot_core_mid_L");
    let travel = mid(first) - rows[tied..].iter().map(mid).fold(f64::INFINITY, f64::min);
    let nearest = rows[tied..].iter().map(|r| number(r, "knot_core_start_L")).fold(1.0, f64::min);
    let length = |r: &Vec<String>| number(r, "knot_core_length_cm");
    let change = length(last) / length(first) - 1.0;
    let (a, b) = (slide.len() / 10, slide.len() * 9 / 10 - 1);
    let (ta, tb) = (number(slide[a], "time_s"), number(slide[b], "time_s"));
    let speed = (mid(slide[a]) - mid(slide[b])) * 42.4 / (tb - ta);
    (travel, nearest, change, speed)
}

#[test]
fn the_tied_knot_slides_toward_the_head_on_es103_because_of_the_targets() {
    let (travel, nearest, change, speed) = slide("tie_slide", &[]);
    assert!(travel >= 0.25, "the core's midpoint moved {travel} L toward the head");
    assert!(nearest <= 0.05, "the core's head-ward end came to {nearest} L only");
    assert!(change.abs() <= 0.3, "the core's length changed by {:.0} %", 100.0 * change);
    assert!((speed / 2.0 - 1.0).abs() <= 0.3, "the knot slid at {speed} cm/s, 2 commanded");
    // The control run: the same slide phase (and tail pull) with zero targets.
    let zero = [
        "--set",
        "phases[2].Thigmotaxis.parameters.head=(0.0, 0.0)",
        "--set",
        "phases[2].Thigmotaxis.parameters.tail=(0.0, 0.0)",
    ];
    let (control, ..) = slide("tie_slide_control", &zero);
    assert!(travel - control >= 0.2, "travel {travel} L with the targets, {control} L without");
}

#[test]
fn the_figure_eight_is_tied_and_held_on_es103() {
    let dir = fresh_dir("tie_figure_eight");
    let scenario = format!("{ROOT}/data/scenarios/figure_eight.ron");
    let output = run_hagfish(["run", &scenario, "--quiet", "--out", &dir.to_string_lossy()]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    let (header, rows) = metrics_table(&dir);
    let tied = rows.iter().position(|r| r[header["phase"]] != "tie").expect("tied");
    let after = &rows[tied..];
    let held = after.iter().filter(|r| r[header["knot"]] == "4_1").count();
    assert!(held as f64 >= 0.99 * after.len() as f64, "held on {held} of {}", after.len());
    for row in after {
        let writhe: f64 = row[header["knot_writhe"]].parse().expect("a writhe");
        assert!(writhe.abs() < 1.5, "frame {}: writhe {writhe} (4_1 is achiral)", row[0]);
    }
    let penetration = rows.iter().map(|r| r[header["max_self_penetration_rel"]].parse::<f64>());
    let deepest = penetration.map(|p| p.expect("a number")).fold(0.0, f64::max);
    assert!(deepest < 0.02, "self penetration {:.2} % of r", 100.0 * deepest);
}
