//! A body's shape at t = 0 read from a file of vertices: a curve another simulator starts from
//! (the overhand knots of Choi, Tong, Jawed & Joo 2021, `data/knots/imc-der/`), so that both
//! start from the same curve. The curve is moved so that its first vertex is the head's joint
//! and turned (by the smallest rotation) so that its first segment runs along +X, the
//! direction the chain leaves the wall; past its last vertex it goes on straight, 2L along its
//! last segment, so that a body longer than the curve ends straight.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DQuat, DVec3};
use hagfish_anatomy::{DataFile, read_data_file};
use serde::{Deserialize, Serialize};

use crate::error::ScenarioError;
use crate::scenario::Scenario;

/// A curve read from a vertex file, another simulator's starting curve: moved so that its
/// first vertex is the head's joint, turned so that its first segment runs along +X, and
/// continued straight for 2L past its last vertex ([`PolylineShape::curve`]).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolylineShape {
    /// The vertex file, relative to the scenario file (absolute once loaded): one vertex per
    /// line, its first three numbers x y z (separated by blanks or commas; further numbers on
    /// the line, such as imc-der's twist angle, are ignored).
    pub file: PathBuf,
    /// Centimetres per unit of the file: 100 for a file in metres.
    #[serde(default = "one")]
    pub cm_per_unit: f64,
    /// The vertices read from `file` (cm, as written); `None` until the scenario is loaded.
    #[serde(skip)]
    pub vertices: Option<Arc<Vec<DVec3>>>,
}

impl PartialEq for PolylineShape {
    /// The same file at the same scale.
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file && self.cm_per_unit == other.cm_per_unit
    }
}

/// The default scale: the file is in centimetres.
fn one() -> f64 {
    1.0
}

impl PolylineShape {
    /// The curve the body is laid along (world frame, cm): the vertices moved to the head and
    /// turned onto +X, then a straight continuation 2 `length_cm` long. Empty before load.
    pub fn curve(&self, length_cm: f64) -> Vec<DVec3> {
        let Some(vertices) = self.vertices.as_deref() else { return Vec::new() };
        let (Some(&first), Some(&second)) = (vertices.first(), vertices.get(1)) else {
            return Vec::new();
        };
        let turn = DQuat::from_rotation_arc((second - first).normalize(), DVec3::X);
        let mut points: Vec<DVec3> = vertices.iter().map(|&v| turn * (v - first)).collect();
        let n = points.len();
        let along = (points[n - 1] - points[n - 2]).normalize();
        points.push(points[n - 1] + along * (2.0 * length_cm));
        points
    }

    /// The arc length of the vertices (cm).
    pub fn length_cm(&self) -> f64 {
        self.vertices.as_deref().map_or(0.0, |v| v.windows(2).map(|w| w[0].distance(w[1])).sum())
    }
}

/// Reads the vertices of the text at `path` (scaled by `cm_per_unit`), skipping blank lines and
/// lines starting with `#`; errors say what is wrong and on which line.
pub(crate) fn read_vertices(path: &Path, cm_per_unit: f64) -> Result<Vec<DVec3>, String> {
    let bytes = read_data_file(path).map_err(|e| e.to_string())?;
    let text = std::str::from_utf8(&bytes).map_err(|e| format!("not UTF-8 text: {e}"))?;
    let mut vertices = Vec::new();
    let data_lines = text.lines().enumerate().filter(|(_, l)| {
        let line = l.trim();
        !line.is_empty() && !line.starts_with('#')
    });
    for (number, line) in data_lines {
        let fields: Vec<&str> =
            line.split(|c: char| c.is_whitespace() || c == ',').filter(|f| !f.is_empty()).collect();
        let values: Result<Vec<f64>, _> = fields.iter().take(3).map(|f| f.parse::<f64>()).collect();
        let at = number + 1;
        match values {
            Ok(v) if v.len() == 3 && v.iter().all(|x| x.is_finite()) => {
                vertices.push(DVec3::new(v[0], v[1], v[2]) * cm_per_unit);
            }
            Ok(_) => return Err(format!("line {at}: expected three finite numbers x y z")),
            Err(e) => return Err(format!("line {at}: {e}")),
        }
    }
    if vertices.len() < 2 {
        return Err(format!("{} vertices: at least 2 are needed", vertices.len()));
    }
    if vertices[0].distance(vertices[1]) == 0.0 {
        return Err("the first two vertices coincide: the curve has no first direction".into());
    }
    Ok(vertices)
}

/// `shape` with its file made absolute (relative to `directory`, the scenario file's) and its
/// vertices read. Errors give the scenario's position of the shape's `file`.
pub(crate) fn resolve_polyline(
    file: &DataFile<Scenario>,
    directory: &Path,
    mut shape: PolylineShape,
) -> Result<PolylineShape, ScenarioError> {
    let path = directory.join(&shape.file);
    let scale = shape.cm_per_unit;
    let vertices = if scale.is_finite() && scale > 0.0 {
        read_vertices(&path, scale)
    } else {
        Err(format!("cm_per_unit = {scale}: expected a positive number"))
    };
    let vertices = vertices.map_err(|reason| ScenarioError::ShapeFile {
        at: file.locate_string("file", &shape.file.to_string_lossy()),
        reason: format!("{}: {reason}", path.display()),
    })?;
    shape.file = std::fs::canonicalize(&path).unwrap_or(path);
    shape.vertices = Some(Arc::new(vertices));
    Ok(shape)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(vertices: Vec<DVec3>) -> PolylineShape {
        PolylineShape { file: "x".into(), cm_per_unit: 1.0, vertices: Some(Arc::new(vertices)) }
    }

    #[test]
    fn the_curve_starts_at_the_head_along_x_and_goes_on_straight() {
        let bent = shape(vec![
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, 3.0, 1.0),
            DVec3::new(1.0, 3.0, 4.0),
        ]);
        let curve = bent.curve(10.0);
        assert_eq!(curve.len(), 4);
        assert!(curve[0].length() < 1e-15 && curve[1].distance(DVec3::X * 2.0) < 1e-12);
        // Distances are kept, and the tail goes on along the last segment for 2L.
        assert!((curve[2].distance(curve[1]) - 3.0).abs() < 1e-12);
        let last = (curve[2] - curve[1]).normalize();
        assert!(curve[3].distance(curve[2] + last * 20.0) < 1e-12);
        assert_eq!(bent.length_cm(), 5.0);
    }

    #[test]
    fn vertex_files_are_read_with_their_scale_and_refused_with_their_line() {
        let dir = std::env::temp_dir().join(format!("hagfish_polyline_{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        let path = dir.join("curve.txt");
        std::fs::write(&path, "# a comment\n0 0 0 7\n0.01, 0, 0\n\n0.01 0.02 0 1 2\n")
            .expect("a file");
        let read = read_vertices(&path, 100.0).expect("a curve");
        assert_eq!(read, [DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 2.0, 0.0)]);
        for (text, said) in [
            ("0 0 0\n1 x 0\n", "line 2"),
            ("0 0 0\n1 0\n", "line 2: expected three"),
            ("0 0 0\n", "1 vertices"),
            ("0 0 0\n0 0 0\n1 0 0\n", "coincide"),
            ("0 0 0\n1 0 inf\n", "line 2: expected three finite"),
        ] {
            std::fs::write(&path, text).expect("a file");
            let error = read_vertices(&path, 1.0).expect_err(text);
            assert!(error.contains(said), "{text:?}: {error}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
