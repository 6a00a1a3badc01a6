//! A run's midline as WCON, the Worm tracker Commons Object Notation that tracked-video tools
//! read (OpenWorm's tracker-commons): one JSON object with `units`, `metadata` and `data`.
//!
//! The one animal (`id` `"1"`) has arrayed `t` (s) and, per frame, `x` and `y` arrays of the
//! body centres from head to tail (cm, as the units say). WCON is planar; the third coordinate
//! is kept in the custom block `@hagfish` of the data entry (`z`, cm, one array per frame, as
//! the WCON rule for custom per-time data asks), with the run's scenario and hashes in a
//! top-level `@hagfish` block. Axes are those of `centreline.csv`.

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use crate::centreline::Centreline;
use crate::error::ReportError;

/// The file `hagfish export wcon DIR` writes when no path is given.
pub const WCON_FILE: &str = "midline.wcon";

/// The WCON object of a run's centreline; `manifest` is the run's `manifest.json` (its
/// scenario, hashes and version go into the metadata), if it has one.
pub fn wcon(centreline: &Centreline, manifest: Option<&Value>) -> Value {
    let frames = centreline.times.len();
    let coordinate = |axis: usize| -> Vec<Vec<f64>> {
        (0..frames)
            .map(|f| {
                let points = &centreline.points[f * centreline.bodies..(f + 1) * centreline.bodies];
                points.iter().map(|p| p[axis]).collect()
            })
            .collect()
    };
    let field = |key: &str| manifest.and_then(|m| m.get(key)).cloned().unwrap_or(Value::Null);
    json!({
        "units": {"t": "s", "x": "cm", "y": "cm", "z": "cm"},
        "metadata": {
            "software": {"name": "hagfish", "version": field("version")},
            "protocol": "simulation: body centres of a hagfish model (docs/outputs.md)",
        },
        "@hagfish": {
            "scenario": field("scenario_name"),
            "scenario_hash": field("scenario_hash"),
            "final_state_hash": field("final_state_hash"),
            "bodies": centreline.bodies,
            "midline": "body centres from the head (index 0) to the tail; z under @hagfish",
        },
        "data": [{
            "id": "1",
            "t": centreline.times,
            "x": coordinate(0),
            "y": coordinate(1),
            "@hagfish": {"z": coordinate(2)},
        }],
    })
}

/// Writes the WCON of the run in `dir` to `path` (default `dir/midline.wcon`); returns the
/// path written.
pub fn export_wcon(dir: &Path, path: Option<&Path>) -> Result<PathBuf, ReportError> {
    let centreline = Centreline::read(&dir.join("centreline.csv"))?;
    let manifest = std::fs::read_to_string(dir.join("manifest.json"))
        .ok()
        .and_then(|text| serde_json::from_str::<Value>(&text).ok());
    let target = path.map_or_else(|| dir.join(WCON_FILE), Path::to_path_buf);
    let text = wcon(&centreline, manifest.as_ref()).to_string();
    crate::outputs::write_file(&target, text.as_bytes())?;
    Ok(target)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_frame_has_one_point_per_body_and_z_is_kept() {
        let line = Centreline {
            times: vec![0.0, 0.1],
            bodies: 2,
            points: vec![[0.0, 1.0, 2.0], [3.0, 4.0, 5.0], [6.0, 7.0, 8.0], [9.0, 10.0, 11.0]],
        };
        let w = wcon(&line, None);
        assert_eq!(w["units"]["x"], "cm");
        let data = &w["data"][0];
        assert_eq!(data["t"], json!([0.0, 0.1]));
        assert_eq!(data["x"], json!([[0.0, 3.0], [6.0, 9.0]]));
        assert_eq!(data["y"], json!([[1.0, 4.0], [7.0, 10.0]]));
        assert_eq!(data["@hagfish"]["z"], json!([[2.0, 5.0], [8.0, 11.0]]));
    }
}
