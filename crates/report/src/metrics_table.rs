//! A run directory's `metrics.csv` (`docs/outputs.md`) as a table: columns by name, numbers
//! parsed on demand (an empty or unparsable field is NaN): what the knot measures read.

use std::path::Path;

use crate::csv::CsvFile;
use crate::error::ReportError;

/// The rows of a `metrics.csv` under its header, as text.
pub(crate) struct MetricsCsv {
    file: CsvFile,
    pub(crate) rows: Vec<Vec<String>>,
}

impl MetricsCsv {
    /// Reads `dir/metrics.csv`.
    pub(crate) fn read(dir: &Path) -> Result<Self, ReportError> {
        let file = CsvFile::open(&dir.join("metrics.csv"))?;
        let mut rows = Vec::new();
        file.for_each_record(|record| {
            rows.push((0..file.header().len()).map(|k| record.text(k).to_owned()).collect());
            Ok(())
        })?;
        Ok(Self { file, rows })
    }

    /// The index of the column `name`.
    pub(crate) fn column(&self, name: &str) -> Result<usize, ReportError> {
        self.file.column(name)
    }

    /// A [`ReportError::Invalid`] of this file: the run has no such measures.
    pub(crate) fn unusable(&self, what: impl Into<String>) -> ReportError {
        ReportError::Invalid { path: self.file.path().to_path_buf(), what: what.into() }
    }
}

/// Field `k` of `row` as a number (NaN if empty or not a number).
pub(crate) fn number(row: &[String], k: usize) -> f64 {
    row[k].trim().parse().unwrap_or(f64::NAN)
}

/// The first row after the tie phase (the frame the knot is tied in), if any.
pub(crate) fn first_after_tie(rows: &[Vec<String>], phase: usize) -> Option<usize> {
    rows.iter().position(|r| r[phase] != "tie")
}
