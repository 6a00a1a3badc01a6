//! A run directory's `metrics.csv` (`docs/outputs.md`) as a table: columns by name, numbers
//! parsed on demand (an empty or unparsable field is NaN).

use std::collections::HashMap;
use std::path::Path;

/// The rows of a `metrics.csv` under its header.
pub(crate) struct MetricsCsv {
    header: HashMap<String, usize>,
    pub(crate) rows: Vec<Vec<String>>,
}

impl MetricsCsv {
    /// Reads `dir/metrics.csv`.
    pub(crate) fn read(dir: &Path) -> Result<Self, String> {
        let path = dir.join("metrics.csv");
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut lines = text.lines();
        let header = lines.next().ok_or("an empty metrics.csv")?;
        Ok(Self {
            header: header.split(',').map(str::to_owned).zip(0..).collect(),
            rows: lines.map(|l| l.split(',').map(str::to_owned).collect()).collect(),
        })
    }

    /// The index of the column `name`.
    pub(crate) fn column(&self, name: &str) -> Result<usize, String> {
        self.header.get(name).copied().ok_or(format!("metrics.csv has no column {name}"))
    }
}

/// Field `k` of `row` as a number (NaN if empty or not a number).
pub(crate) fn number(row: &[String], k: usize) -> f64 {
    row[k].parse().unwrap_or(f64::NAN)
}

/// The first row after the tie phase (the frame the knot is tied in), if any.
pub(crate) fn first_after_tie(rows: &[Vec<String>], phase: usize) -> Option<usize> {
    rows.iter().position(|r| r[phase] != "tie")
}
