//! A run directory as `hagfish run` writes it, read into memory: the three CSV files it
//! always has, and the optional ones (`scenario.ron`, `manifest.json`, `contacts.csv`).

use std::path::{Path, PathBuf};

use crate::centreline::Centreline;
use crate::csv::CsvFile;
use crate::error::ReportError;
use crate::forces::ThigmoForces;
use crate::metrics::Metrics;
use crate::radii::Radii;

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
    /// The text of `scenario.ron`, if present.
    pub scenario: Option<String>,
    /// The text of `manifest.json`, if present.
    pub manifest: Option<String>,
    /// A one-line description of `contacts.csv` (rows and columns, or why it is unreadable),
    /// if present.
    pub contacts: Option<String>,
}

impl RunDir {
    /// Reads the run directory `dir`. The three CSV files are required; the optional files
    /// may be absent, and an unreadable `contacts.csv` is described rather than an error.
    pub fn read(dir: &Path) -> Result<Self, ReportError> {
        let centreline = Centreline::read(&dir.join("centreline.csv"))?;
        let metrics = Metrics::read(&dir.join("metrics.csv"))?;
        let forces = ThigmoForces::read(&dir.join("forces.csv"))?;
        let radii = Radii::for_run(&dir.join("scenario.ron"), centreline.bodies);
        let contacts_path = dir.join("contacts.csv");
        let contacts = contacts_path.exists().then(|| describe_csv(&contacts_path));
        Ok(Self {
            dir: dir.to_path_buf(),
            centreline,
            metrics,
            forces,
            radii,
            scenario: read_optional(&dir.join("scenario.ron"))?,
            manifest: read_optional(&dir.join("manifest.json"))?,
            contacts,
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
    let described = CsvFile::read(path).and_then(|file| {
        let rows = file.records().collect::<Result<Vec<_>, _>>()?.len();
        Ok(format!("{rows} rows; columns {}", file.header().join(", ")))
    });
    described.unwrap_or_else(|e| e.to_string())
}
