//! ParaView export: one legacy VTK file per frame (`vtk/frame_NNNN.vtk`, POLYDATA: the body
//! centres as one LINES cell with a `radius_cm` point field, cm), the series index
//! `vtk/centreline.vtk.series` (ParaView's JSON file-series format, times in s) and, when the
//! run has obstacles, their wireframes (POLYDATA LINES, cm): `vtk/obstacles.vtk` when they
//! stand still, else one `vtk/obstacles_NNNN.vtk` per frame indexed by
//! `vtk/obstacles.vtk.series`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::centreline::Centreline;
use crate::error::ReportError;
use crate::obstacles::Wireframe;
use crate::outputs::write_file;

/// Name of the series index inside the VTK directory.
pub const SERIES: &str = "centreline.vtk.series";
/// Name of the still obstacles' file inside the VTK directory.
pub const OBSTACLES: &str = "obstacles.vtk";
/// Name of the moving obstacles' series index inside the VTK directory.
pub const OBSTACLE_SERIES: &str = "obstacles.vtk.series";

/// The legacy VTK text of the obstacles' wireframes: one LINES cell per polyline.
pub fn obstacles_text(wireframe: &Wireframe) -> String {
    let n: usize = wireframe.iter().map(Vec::len).sum();
    let mut text = format!(
        "# vtk DataFile Version 3.0\nhagfish obstacles (cm)\nASCII\nDATASET POLYDATA\n\
         POINTS {n} float\n"
    );
    for p in wireframe.iter().flatten() {
        let _ = writeln!(text, "{} {} {}", p[0] as f32, p[1] as f32, p[2] as f32);
    }
    let _ = writeln!(text, "LINES {} {}", wireframe.len(), n + wireframe.len());
    let mut first = 0;
    for polyline in wireframe {
        let _ = write!(text, "{}", polyline.len());
        for i in first..first + polyline.len() {
            let _ = write!(text, " {i}");
        }
        let _ = writeln!(text);
        first += polyline.len();
    }
    text
}

/// The legacy VTK text of frame `f`.
pub fn frame_text(centreline: &Centreline, radii: &[f64], f: usize) -> String {
    let points = centreline.frame(f);
    let n = points.len();
    let mut text = format!(
        "# vtk DataFile Version 3.0\nhagfish centreline, frame {f}, t = {} s (cm)\n\
         ASCII\nDATASET POLYDATA\nPOINTS {n} float\n",
        centreline.times[f]
    );
    for p in points {
        let _ = writeln!(text, "{} {} {}", p[0] as f32, p[1] as f32, p[2] as f32);
    }
    let _ = write!(text, "LINES 1 {}\n{n}", n + 1);
    for i in 0..n {
        let _ = write!(text, " {i}");
    }
    let _ = write!(text, "\nPOINT_DATA {n}\nSCALARS radius_cm float 1\nLOOKUP_TABLE default\n");
    for r in radii {
        let _ = writeln!(text, "{}", *r as f32);
    }
    text
}

/// The file name of frame `f`.
pub fn frame_name(f: usize) -> String {
    format!("frame_{f:04}.vtk")
}

/// The file name of the obstacles at frame `f` (when they move).
pub fn obstacle_frame_name(f: usize) -> String {
    format!("obstacles_{f:04}.vtk")
}

/// The `.vtk.series` JSON naming every frame's file (as `name` names it) and time.
pub fn series_text(centreline: &Centreline, name: fn(usize) -> String) -> String {
    let files: Vec<serde_json::Value> = centreline
        .times
        .iter()
        .enumerate()
        .map(|(f, t)| serde_json::json!({ "name": name(f), "time": t }))
        .collect();
    let series = serde_json::json!({ "file-series-version": "1.0", "files": files });
    format!("{series:#}\n")
}

/// Whether `name` is one of the files this module writes (a frame or the series index).
pub fn is_own_file(name: &str) -> bool {
    let numbered = |prefix: &str| {
        let digits = name.strip_prefix(prefix).and_then(|rest| rest.strip_suffix(".vtk"));
        digits.is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
    };
    [SERIES, OBSTACLES, OBSTACLE_SERIES].contains(&name)
        || numbered("frame_")
        || numbered("obstacles_")
}

/// The obstacles' wireframes of a run for [`write`]: one for the whole run, or one per frame
/// when an obstacle moves.
#[derive(Clone, Debug, PartialEq)]
pub enum ObstacleFrames {
    /// They stand still (an empty wireframe: the run has none).
    Still(Wireframe),
    /// Where they are at each frame.
    Moving(Vec<Wireframe>),
}

/// Writes every frame, the series index and the obstacles (if there are any) into `dir`
/// (created if missing), after removing the files of an earlier run (so that none of a
/// longer run lingers); other files in `dir` are left alone. Returns the series index's path
/// and the number of frame files.
pub fn write(
    centreline: &Centreline,
    radii: &[f64],
    obstacles: &ObstacleFrames,
    dir: &Path,
) -> Result<(PathBuf, usize), ReportError> {
    std::fs::create_dir_all(dir).map_err(ReportError::write(dir))?;
    for path in crate::outputs::own_files_in(dir, is_own_file)? {
        std::fs::remove_file(&path).map_err(ReportError::write(&path))?;
    }
    for f in 0..centreline.frames() {
        let path = dir.join(frame_name(f));
        write_file(&path, frame_text(centreline, radii, f).as_bytes())?;
    }
    match obstacles {
        ObstacleFrames::Still(wireframe) if wireframe.is_empty() => {}
        ObstacleFrames::Still(wireframe) => {
            write_file(&dir.join(OBSTACLES), obstacles_text(wireframe).as_bytes())?;
        }
        ObstacleFrames::Moving(frames) => {
            for (f, wireframe) in frames.iter().enumerate() {
                let path = dir.join(obstacle_frame_name(f));
                write_file(&path, obstacles_text(wireframe).as_bytes())?;
            }
            let series = series_text(centreline, obstacle_frame_name);
            write_file(&dir.join(OBSTACLE_SERIES), series.as_bytes())?;
        }
    }
    let path = dir.join(SERIES);
    write_file(&path, series_text(centreline, frame_name).as_bytes())?;
    Ok((path, centreline.frames()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_files::two_frames;

    #[test]
    fn a_frame_is_polydata_with_one_polyline_and_a_radius_per_point() {
        let text = frame_text(&two_frames(), &[0.5, 0.75, 0.25], 1);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "# vtk DataFile Version 3.0");
        assert_eq!(&lines[2..5], &["ASCII", "DATASET POLYDATA", "POINTS 3 float"]);
        assert_eq!(lines[7], "2 1.5 -0.25");
        assert_eq!(&lines[8..10], &["LINES 1 4", "3 0 1 2"]);
        assert_eq!(&lines[10..12], &["POINT_DATA 3", "SCALARS radius_cm float 1"]);
        assert_eq!(&lines[13..], &["0.5", "0.75", "0.25"]);
    }

    #[test]
    fn only_frames_and_the_series_are_own_files() {
        assert!(is_own_file("frame_0000.vtk") && is_own_file("frame_12345.vtk"));
        assert!(is_own_file(SERIES) && is_own_file(OBSTACLES) && is_own_file(OBSTACLE_SERIES));
        assert!(is_own_file("obstacles_0003.vtk") && !is_own_file("obstacles_.vtk"));
        for other in ["frame_.vtk", "frame_01a.vtk", "mine.vtk", "frame_0001.vtk.bak", "notes"] {
            assert!(!is_own_file(other), "{other}");
        }
    }

    #[test]
    fn the_obstacles_are_one_lines_cell_per_polyline() {
        let wireframe = vec![
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
            vec![[0.0; 3], [0.0, 1.0, 0.0], [0.0, 1.0, 1.0]],
        ];
        let text = obstacles_text(&wireframe);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(&lines[2..5], &["ASCII", "DATASET POLYDATA", "POINTS 5 float"]);
        assert_eq!(&lines[10..], &["LINES 2 7", "2 0 1", "3 2 3 4"]);
    }

    #[test]
    fn still_obstacles_get_one_file_and_moving_ones_a_series_that_replaces_it() {
        let dir = crate::test_files::dir("vtk-obstacles");
        let (centreline, radii) = (two_frames(), [0.5, 0.75, 0.25]);
        let line = |y: f64| vec![vec![[0.0, y, 0.0], [1.0, y, 0.0]]];
        write(&centreline, &radii, &ObstacleFrames::Still(line(0.0)), &dir).expect("writes");
        assert!(dir.join(OBSTACLES).exists() && !dir.join(OBSTACLE_SERIES).exists());
        let moving = ObstacleFrames::Moving(vec![line(0.0), line(1.0)]);
        write(&centreline, &radii, &moving, &dir).expect("writes");
        assert!(!dir.join(OBSTACLES).exists(), "the still file of the earlier run is gone");
        let second = std::fs::read_to_string(dir.join(obstacle_frame_name(1))).expect("frame 1");
        assert!(second.contains("\n0 1 0\n1 1 0\n"), "{second}");
        let series = std::fs::read_to_string(dir.join(OBSTACLE_SERIES)).expect("series");
        assert!(series.contains("obstacles_0001.vtk"), "{series}");
        write(&centreline, &radii, &ObstacleFrames::Still(Vec::new()), &dir).expect("writes");
        assert!(!dir.join(OBSTACLE_SERIES).exists() && !dir.join(obstacle_frame_name(0)).exists());
    }

    #[test]
    fn the_series_names_each_frame_with_its_time() {
        let series: serde_json::Value =
            serde_json::from_str(&series_text(&two_frames(), frame_name)).expect("valid JSON");
        assert_eq!(series["file-series-version"], "1.0");
        assert_eq!(series["files"][1]["name"], "frame_0001.vtk");
        assert_eq!(series["files"][1]["time"], 0.5);
        assert_eq!(series["files"].as_array().map(Vec::len), Some(2));
    }
}
