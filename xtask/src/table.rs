//! The result table of a regression check: one row per scenario and metric.

use crate::metrics::Value;

/// One compared metric.
pub struct Row {
    /// Scenario name.
    pub scenario: String,
    /// Metric name.
    pub metric: String,
    /// The golden's value (`None`: no golden).
    pub golden: Option<Value>,
    /// This run's value (`None`: no such metric in this run).
    pub now: Option<Value>,
    /// The tolerance, described.
    pub tolerance: String,
    /// `Some(true)` ok, `Some(false)` FAIL, `None` not compared.
    pub ok: Option<bool>,
}

fn show(value: Option<&Value>) -> String {
    match value {
        None => "(none)".into(),
        Some(Value::Missing) => "-".into(),
        Some(Value::Number(x)) => format!("{x:.6}"),
        Some(Value::Text(text)) => text.clone(),
    }
}

/// Prints `rows` as an aligned table.
pub fn print(rows: &[Row]) {
    let header = ["scenario", "metric", "golden", "now", "tol", "result"].map(String::from);
    let cells: Vec<[String; 6]> = rows
        .iter()
        .map(|r| {
            let result = match r.ok {
                Some(true) => "ok",
                Some(false) => "FAIL",
                None => "skipped (other platform)",
            };
            [
                r.scenario.clone(),
                r.metric.clone(),
                show(r.golden.as_ref()),
                show(r.now.as_ref()),
                r.tolerance.clone(),
                result.to_owned(),
            ]
        })
        .collect();
    let width = |c: usize| {
        cells.iter().chain([&header]).map(|row| row[c].chars().count()).max().unwrap_or(0)
    };
    let widths: Vec<usize> = (0..6).map(width).collect();
    for row in [&header].into_iter().chain(&cells) {
        let line: Vec<String> =
            row.iter().zip(&widths).map(|(cell, w)| format!("{cell:<w$}")).collect();
        println!("{}", line.join("  ").trim_end());
    }
}
