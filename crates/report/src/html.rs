//! `report.html`: one self-contained page (no network): summary table, the 3-D view
//! (hand-written WebGL over the embedded centreline, `assets/viewer.js`), the animation and
//! plots as base64 images, the scenario and manifest texts. Scripts record errors
//! (`assets/errors.js`) and set `<body data-status>` to `ok` once everything rendered.

use std::collections::HashMap;
use std::fmt::Write as _;

use base64::Engine as _;
use base64::engine::general_purpose::STANDARD;

use crate::animation;
use crate::obstacles;
use crate::plots::Plot;
use crate::run_dir::RunDir;
use crate::section::Section;
use crate::summary;

const TEMPLATE: &str = include_str!("../assets/report.html");
const ERRORS_JS: &str = include_str!("../assets/errors.js");
const VIEWER_JS: &str = include_str!("../assets/viewer.js");

/// Escapes text for HTML element content and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Replaces every `{{name}}` of `template` by `values[name]` in one pass (so replaced text is
/// never scanned again); an unknown name is left as is.
fn fill(template: &str, values: &HashMap<&str, String>) -> String {
    let mut out =
        String::with_capacity(template.len() + values.values().map(String::len).sum::<usize>());
    let mut rest = template;
    while let Some(start) = rest.find("{{") {
        out.push_str(&rest[..start]);
        let after = &rest[start + 2..];
        match after.find("}}").and_then(|end| values.get(&after[..end]).map(|v| (end, v))) {
            Some((end, value)) => {
                out.push_str(value);
                rest = &after[end + 2..];
            }
            None => {
                out.push_str("{{");
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The run data the viewer reads: frames, bodies, times, radii, the body centres as
/// base64 little-endian f32 (frame-major, x y z), per frame its phase and knot (of the
/// frames the run directory was read with, [`RunDir::frames`]), and the obstacles.
///
/// The centres are the bulk (32 MB of base64 for 201 frames of 10 000 bodies), so they are
/// encoded straight into the returned text where the rest of the JSON leaves room for them,
/// rather than copied through a JSON value, its text and its escaped text (base64 needs no
/// escaping in JSON, and has no `</`).
fn run_data(run: &RunDir) -> String {
    let c = &run.centreline;
    let m = &run.metrics;
    let states: Vec<String> = run
        .frames
        .kept(m.frames())
        .map(|f| format!("phase {}, knot {}", m.phase[f], m.knot[f]))
        .collect();
    // Each obstacle: its wireframe's segments (vertex pairs, cm) at offset zero, and its pose
    // at each frame (none when it stands still): R row by row, then t, 12 numbers a frame.
    let obstacles: Vec<serde_json::Value> = obstacles::tracks(run)
        .iter()
        .map(|track| {
            let segments = track.lines.iter().flat_map(|line| line.windows(2).flatten());
            let poses = track.poses.iter().flat_map(|pose| {
                let r = glam::DMat3::from_quat(pose.rotation).transpose().to_cols_array();
                r.into_iter().chain(pose.translation.to_array())
            });
            serde_json::json!({
                "segments": segments.flatten().copied().collect::<Vec<f64>>(),
                "poses": poses.collect::<Vec<f64>>(),
            })
        })
        .collect();
    let rest = serde_json::json!({
        "frames": c.frames(),
        "bodies": c.bodies,
        "times": c.times,
        "radii": run.radii.values,
        "points": "",
        "states": states,
        "obstacles": obstacles,
    });
    let rest = script_safe(&rest.to_string());
    let (before, after) = rest.split_once(POINTS_PLACE).expect("the JSON has its points member");
    let mut bytes = Vec::with_capacity(12 * c.points.len());
    bytes.extend(c.points.iter().flatten().flat_map(|v| (*v as f32).to_le_bytes()));
    let encoded = base64::encoded_len(bytes.len(), true).unwrap_or(0);
    let mut data = String::with_capacity(rest.len() + encoded);
    // `"points":"` and `"`, the centres encoded between them.
    let (open, close) = POINTS_PLACE.split_at(POINTS_PLACE.len() - 1);
    data.push_str(before);
    data.push_str(open);
    STANDARD.encode_string(&bytes, &mut data);
    data.push_str(close);
    data.push_str(after);
    data
}

/// `json` made safe to embed in a `<script>` element: `<`, `>` and `&` (which JSON holds only
/// inside strings) written as `\u` escapes, so that no `</script`, `<!--` or `<script` from a
/// user-named field (a phase name) can close or confuse the element, and U+2028/U+2029 too,
/// which older JavaScript does not allow in strings. The text still parses to the same value.
fn script_safe(json: &str) -> String {
    const ESCAPES: [(char, &str); 5] = [
        ('<', "\\u003c"),
        ('>', "\\u003e"),
        ('&', "\\u0026"),
        ('\u{2028}', "\\u2028"),
        ('\u{2029}', "\\u2029"),
    ];
    let mut safe = String::with_capacity(json.len());
    for c in json.chars() {
        match ESCAPES.iter().find(|(special, _)| *special == c) {
            Some((_, escaped)) => safe.push_str(escaped),
            None => safe.push(c),
        }
    }
    safe
}

/// The `points` member of [`run_data`]'s JSON before the centres are encoded into it.
const POINTS_PLACE: &str = "\"points\":\"\"";

fn preformatted(text: Option<&String>, missing: &str) -> String {
    text.map_or_else(|| format!("<p>{missing}</p>"), |t| format!("<pre>{}</pre>", escape(t)))
}

/// The page for `run` with its drawn `plots`, `gif` animation and the `sections` other crates
/// made (after the plots).
pub fn page(run: &RunDir, plots: &[Plot], gif: &[u8], sections: &[Section]) -> String {
    let mut table = String::from("<table>\n");
    for (key, value) in summary::rows(&run.metrics, run.tension.as_ref()) {
        let _ = writeln!(table, "<tr><th>{}</th><td>{}</td></tr>", escape(&key), escape(&value));
    }
    table.push_str("</table>");
    let figures: String =
        plots.iter().map(|plot| crate::section::figure(plot, Some("plots/"))).collect();
    let files = format!(
        "<ul><li>Body radii: {}.</li><li>contacts.csv: {}.</li></ul>",
        escape(&run.radii.source),
        escape(run.contacts.as_deref().unwrap_or("absent"))
    );
    let shown = animation::shown_frames(run.centreline.frames()).len();
    let mut caption = format!(
        "{shown} of {} frames at {} × real time (animation.gif).",
        run.centreline.frames(),
        animation::SPEED_UP
    );
    if run.frames.stride > 1 {
        let _ = write!(
            caption,
            " The 3-D view, the animation, the kymographs, run.glb and vtk/ hold one frame in {} \
             of the run's {} and its last (a run of more frames × bodies than {} would not fit \
             the report's memory; every frame is in centreline.csv).",
            run.frames.stride,
            run.metrics.frames(),
            crate::frame_selection::BODY_FRAME_BUDGET,
        );
    }
    let values = HashMap::from([
        ("title", escape(&run.dir.display().to_string())),
        ("errors_js", ERRORS_JS.to_string()),
        ("summary", table),
        ("animation", STANDARD.encode(gif)),
        ("animation_caption", escape(&caption)),
        ("plots", figures),
        ("sections", sections.iter().map(Section::to_html).collect()),
        ("scenario", preformatted(run.scenario.as_ref(), "No scenario.ron in the run directory.")),
        ("manifest", preformatted(run.manifest.as_ref(), "No manifest.json in the run directory.")),
        ("files", files),
        ("data", run_data(run)),
        ("viewer_js", VIEWER_JS.to_string()),
    ]);
    fill(TEMPLATE, &values)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_viewer_gets_each_obstacle_with_its_segments_and_poses() {
        let dir = crate::test_files::synthetic("viewer-obstacles");
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let form = std::fs::read_to_string(root.join("data/scenarios/form.ron")).expect("form");
        let obstacles = "Scenario(\n    obstacles: [Sphere(centre: (1.0, 2.0, 3.0), radius: 0.5), \
                         Moving(shape: Sphere(centre: (0.0, 0.0, 0.0), radius: 1.0), \
                         path: [(0.0, (0.0, 0.0, 0.0)), (1.0, (1.0, 0.0, 0.0))], \
                         spin: Some((axis: (0.0, 0.0, 1.0), rate_rad_per_s: 1.0)))],";
        std::fs::write(dir.join("scenario.ron"), form.replacen("Scenario(", obstacles, 1))
            .expect("write");
        let run = RunDir::read(&dir).expect("reads");
        let data: serde_json::Value = serde_json::from_str(&run_data(&run)).expect("JSON");
        let obstacles = data["obstacles"].as_array().expect("obstacles");
        assert_eq!(obstacles.len(), 2);
        let segments = obstacles[0]["segments"].as_array().expect("segments");
        assert_eq!(segments.len() % 6, 0, "vertex pairs of x, y, z");
        assert!(obstacles[0]["poses"].as_array().is_some_and(Vec::is_empty), "it stands still");
        let poses = obstacles[1]["poses"].as_array().expect("poses");
        assert_eq!(poses.len(), 12 * run.centreline.frames(), "one pose per frame");
        // The last frame's R row by row: a turn by ωt about z.
        let last = &poses[poses.len() - 12..];
        let t = run.centreline.times[run.centreline.frames() - 1];
        let row0 = [t.cos(), -t.sin(), 0.0];
        for (value, expected) in last[..3].iter().zip(row0) {
            let value = value.as_f64().expect("a number");
            assert!((value - expected).abs() < 1e-12, "R's first row: {value} against {expected}");
        }
    }

    #[test]
    fn escape_covers_markup_characters() {
        assert_eq!(
            escape(r#"<a href="x">&'</a>"#),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;"
        );
    }

    #[test]
    fn embedded_json_cannot_close_or_open_a_script_element() {
        let name = "<!--<script></script>&\u{2028}";
        let json = serde_json::json!({ "states": [format!("phase {name}")] }).to_string();
        let safe = script_safe(&json);
        assert!(!safe.contains(['<', '>', '&', '\u{2028}']), "{safe}");
        let back: serde_json::Value = serde_json::from_str(&safe).expect("still JSON");
        assert_eq!(back["states"][0], format!("phase {name}"));
    }

    #[test]
    fn fill_substitutes_once_and_keeps_unknown_names() {
        let values = HashMap::from([("a", "{{b}}".to_string()), ("b", "B".to_string())]);
        assert_eq!(fill("x{{a}}y{{b}}z{{c}}", &values), "x{{b}}yBz{{c}}");
        assert_eq!(fill("{{a", &values), "{{a");
    }

    #[test]
    fn every_placeholder_of_the_template_is_known() {
        let names = [
            "title",
            "errors_js",
            "summary",
            "animation",
            "animation_caption",
            "plots",
            "sections",
            "scenario",
            "manifest",
            "files",
            "data",
            "viewer_js",
        ];
        let values: HashMap<&str, String> = names.iter().map(|n| (*n, String::new())).collect();
        let filled = fill(TEMPLATE, &values);
        assert!(!filled.contains("{{"), "an unknown placeholder is left");
        for name in names {
            assert!(TEMPLATE.contains(&format!("{{{{{name}}}}}")), "{name} is unused");
        }
    }
}
