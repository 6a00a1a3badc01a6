//! A run directory as `hagfish run` writes it, read into memory: the three CSV files it
//! always has, and the optional ones (`scenario.ron`, `manifest.json`, `contacts.csv`).

use std::path::{Path, PathBuf};

use hagfish_geometry::MovingObstacle;

use crate::centreline::Centreline;
use crate::csv::CsvFile;
use crate::error::ReportError;
use crate::forces::ThigmoForces;
use crate::frame_selection::{BODY_FRAME_BUDGET, FrameSelection};
use crate::metrics::Metrics;
use crate::obstacles;
use crate::radii::Radii;
use crate::tension::Tension;

/// Everything read from a run directory.
#[derive(Clone, Debug)]
pub struct RunDir {
    /// The directory.
    pub dir: PathBuf,
    /// `centreline.csv`.
    pub centreline: Centreline,
    /// `metrics.csv`.
    pub metrics: Metrics,
    /// The `thigmo` group of `forces.csv`.
    pub forces: ThigmoForces,
    /// The body radii (from `scenario.ron` if it gives them).
    pub radii: Radii,
    /// The obstacles of `scenario.ron`, with their paths (none without it).
    pub obstacles: Vec<MovingObstacle>,
    /// The text of `scenario.ron`, if present.
    pub scenario: Option<String>,
    /// The text of `manifest.json`, if present.
    pub manifest: Option<String>,
    /// A one-line description of `contacts.csv` (rows and columns, or why it is unreadable),
    /// if present.
    pub contacts: Option<String>,
    /// The tension column of `internal.csv`, if present (runs made before it existed lack
    /// it).
    pub tension: Option<Tension>,
    /// The frames `centreline`, `forces` and `tension` hold (`metrics` holds every frame):
    /// all of them unless frames × bodies exceed [`BODY_FRAME_BUDGET`].
    pub frames: FrameSelection,
}

impl RunDir {
    /// Reads the run directory `dir`. The three CSV files are required; the optional files
    /// may be absent, and an unreadable `contacts.csv` is described rather than an error.
    pub fn read(dir: &Path) -> Result<Self, ReportError> {
        Self::read_within(dir, BODY_FRAME_BUDGET)
    }

    /// [`RunDir::read`] holding about `budget` body centres at most ([`FrameSelection`]).
    pub(crate) fn read_within(dir: &Path, budget: usize) -> Result<Self, ReportError> {
        let centreline_path = dir.join("centreline.csv");
        let bodies = Centreline::first_frame_bodies(&centreline_path)?;
        let metrics = Metrics::read(&dir.join("metrics.csv"))?;
        let frames = FrameSelection::within(metrics.frames(), bodies, budget);
        let centreline = Centreline::read_selected(&centreline_path, frames)?;
        let forces = ThigmoForces::read_selected(&dir.join("forces.csv"), frames)?;
        let radii = Radii::for_run(&dir.join("scenario.ron"), centreline.bodies);
        let contacts_path = dir.join("contacts.csv");
        let contacts = contacts_path.exists().then(|| describe_csv(&contacts_path));
        let internal = dir.join("internal.csv");
        let tension =
            internal.exists().then(|| Tension::read_selected(&internal, frames)).transpose()?;
        Ok(Self {
            dir: dir.to_path_buf(),
            centreline,
            metrics,
            forces,
            radii,
            obstacles: obstacles::of_run(&dir.join("scenario.ron")),
            scenario: read_optional(&dir.join("scenario.ron"))?,
            manifest: read_optional(&dir.join("manifest.json"))?,
            contacts,
            tension,
            frames,
        })
    }
}

/// The text of `path`, or `None` if it does not exist.
fn read_optional(path: &Path) -> Result<Option<String>, ReportError> {
    match std::fs::read_to_string(path) {
        Ok(text) => Ok(Some(text)),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(source) => Err(ReportError::Read { path: path.to_path_buf(), source }),
    }
}

/// "N rows; columns a, b, c", or the error that reading it gave.
fn describe_csv(path: &Path) -> String {
    let described = CsvFile::open(path).and_then(|file| {
        let rows = file.count_records()?;
        Ok(format!("{rows} rows; columns {}", file.header().join(", ")))
    });
    described.unwrap_or_else(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_files::synthetic;

    #[test]
    fn reads_the_files_hagfish_run_writes_and_skips_absent_optional_ones() {
        let dir = synthetic("plain");
        let run = RunDir::read(&dir).expect("reads");
        assert_eq!((run.centreline.frames(), run.centreline.bodies), (3, 4));
        assert_eq!(run.metrics.self_contacts, vec![0.0, 1.0, 2.0]);
        assert_eq!(run.metrics.knot_position, vec![None; 3]);
        assert_eq!((run.forces.frames(), run.forces.joints), (3, 2));
        assert_eq!(run.forces.values[1][2 * 2 + 1], 3.0, "frame 2, joint 1, Y");
        assert_eq!((run.scenario, run.manifest, run.contacts), (None, None, None));
        assert!(run.radii.source.starts_with("constant"), "{}", run.radii.source);

        std::fs::write(dir.join("manifest.json"), "{\"version\": 1}").expect("write");
        std::fs::write(dir.join("contacts.csv"), "frame,a\n0,1\n1,2\n").expect("write");
        let run = RunDir::read(&dir).expect("reads");
        assert_eq!(run.manifest.as_deref(), Some("{\"version\": 1}"));
        assert_eq!(run.contacts.as_deref(), Some("2 rows; columns frame, a"));
    }

    #[test]
    fn a_run_beyond_the_budget_is_held_one_frame_in_s_and_its_last() {
        let dir = synthetic("budget");
        // 3 frames of 4 bodies within 6 centres: frames 0 and 2 (stride 2, the last).
        let run = RunDir::read_within(&dir, 6).expect("reads");
        assert_eq!(run.frames, FrameSelection { stride: 2, last: Some(2) });
        assert_eq!(run.centreline.times, [0.0, 0.2]);
        assert_eq!(run.centreline.frame(1), RunDir::read(&dir).expect("reads").centreline.frame(2));
        assert_eq!((run.forces.frames(), run.metrics.frames()), (2, 3));
        assert_eq!(run.forces.values[1][2 + 1], 3.0, "frame 2, joint 1, Y");
        let page = crate::html::page(&run, &[], &[], &[]);
        assert!(page.contains("one frame in 2 of the run&#39;s 3 and its last"), "caption");
        assert!(page.contains(r#""states":["phase form, knot 0_1","phase form, knot 0_1"]"#));
    }

    #[test]
    fn a_missing_file_or_column_is_an_error_naming_the_file() {
        let dir = synthetic("broken");
        let metrics = std::fs::read_to_string(dir.join("metrics.csv")).expect("read");
        std::fs::write(dir.join("metrics.csv"), metrics.replacen("knot_position_cm", "kp", 1))
            .expect("write");
        let e = RunDir::read(&dir).expect_err("a column is missing").to_string();
        assert!(e.contains("metrics.csv:1:") && e.contains("knot_position_cm"), "{e}");
        std::fs::remove_file(dir.join("forces.csv")).expect("remove");
        std::fs::write(dir.join("metrics.csv"), metrics).expect("write");
        let e = RunDir::read(&dir).expect_err("forces.csv is missing").to_string();
        assert!(e.contains("forces.csv") && e.contains("cannot read"), "{e}");
    }
}
