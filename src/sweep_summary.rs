//! What the runs of a sweep say together, written by [`collect`] into the sweep folder:
//! - `summary.csv`: one row per planned run — its id, grid point and replicate index, the value
//!   of each swept parameter, then [`RunRow`]'s columns (a run not made yet has status
//!   `missing` and empty values);
//! - `intervals.csv`: per grid point and statistic, over the point's ended runs (completed,
//!   diverged or tie failed), the mean, the standard deviation and a 95 % bootstrap-t interval
//!   of the mean ([`hagfish_stats::mean_interval`], from [`MIN_VALUES_FOR_INTERVAL`] values
//!   on) of every numeric column of [`RunRow`]; and
//!   the shares of runs that tied, held and slid ([`Share`]) with their Wilson intervals;
//! - `plots/`: each numeric statistic against each swept parameter whose values are numbers
//!   that vary, one point per run, with each grid point's mean and interval drawn where it has
//!   replicates.
//!
//! The knot runs are chaotic, so a difference between two grid points is supported only where
//! their intervals say so; a point of one run has no interval.

use std::path::Path;

use hagfish_report::{IntervalBar, Scatter, SlideBounds};

use crate::CliError;
use crate::manifest::MANIFEST_FILE;
use crate::study::RunRow;
use crate::sweep::Plan;

/// The table of runs [`collect`] writes.
pub const SUMMARY_FILE: &str = "summary.csv";

/// The table of grid points [`collect`] writes.
pub const INTERVALS_FILE: &str = "intervals.csv";

/// The confidence level of every interval.
pub const LEVEL: f64 = 0.95;

/// Bootstrap resamples per interval: (B + 1)·(1 − [`LEVEL`])/2 is a whole number, Hall's
/// condition under which a finite B changes the coverage least.
pub const RESAMPLES: usize = 3999;

/// The fewest finite values a mean's interval is drawn from. The bootstrap-t interval's
/// coverage at nominal 95 % (20 000 simulated studies, `crates/stats/src/bootstrap.rs`): 0.81
/// for a normal mean at n = 3 — with intervals hundreds of times the spread when a resample's
/// s* is tiny — against 0.944 at n = 5 and 0.949 at n = 8 (0.927 and 0.935 for exponential
/// data). Below 5 values the table gives the mean and sd but no interval.
pub const MIN_VALUES_FOR_INTERVAL: usize = 5;

/// The columns of `intervals.csv` after the grid point's index and parameter values.
pub const INTERVAL_COLUMNS: [&str; 8] =
    ["runs", "statistic", "n", "mean", "sd", "ci_low", "ci_high", "level"];

/// The statuses of runs that have ended, the only ones a grid point's statistics count.
const ENDED: [&str; 3] = ["completed", "diverged", "tie_failed"];

/// A share of a grid point's ended runs, with its Wilson interval in `intervals.csv`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Share {
    /// The run ended with a knot (`tied_at_s` is set).
    Tied,
    /// Tied, and the knot shows on at least [`SlideBounds::TREFOIL`]`.held` (99 %) of the
    /// frames from the tie on.
    Held,
    /// Held, and the core's midpoint travelled at least [`SlideBounds::TREFOIL`]`.travel`
    /// (0.25 L) toward the head.
    Slid,
}

impl Share {
    /// Every share, in the order of the table.
    pub const ALL: [Share; 3] = [Share::Tied, Share::Held, Share::Slid];

    /// Its statistic's name in `intervals.csv`.
    pub fn name(self) -> &'static str {
        match self {
            Share::Tied => "tied_share",
            Share::Held => "held_share",
            Share::Slid => "slid_share",
        }
    }

    /// Whether the run of `row` counts in this share.
    pub fn counts(self, row: &RunRow) -> bool {
        let bounds = SlideBounds::TREFOIL;
        let tied = row.tied_at_s.is_some();
        let held = tied && row.knot_held_fraction.is_some_and(|h| h >= bounds.held);
        match self {
            Share::Tied => tied,
            Share::Held => held,
            Share::Slid => held && row.core_travel_l.is_some_and(|t| t >= bounds.travel),
        }
    }
}

/// What [`collect`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct Collected {
    /// The swept parameters' paths.
    pub parameters: Vec<String>,
    /// The planned runs.
    pub runs: usize,
    /// Of those, the runs not made yet.
    pub missing: usize,
    /// The rows of `intervals.csv`.
    pub points: Vec<PointStatistic>,
}

impl Collected {
    /// A few lines per grid point to read at the terminal: its parameters, its ended runs,
    /// the shares that tied and slid, and the knot's speed and travel with their intervals.
    pub fn table(&self) -> String {
        let statistic = |point: usize, name: &str| {
            self.points.iter().find(|p| p.point == point && p.statistic == name)
        };
        let shown = |p: Option<&PointStatistic>| match p {
            Some(PointStatistic { mean: Some(mean), interval: Some((low, high)), .. }) => {
                format!("{mean:.3} [{low:.3}, {high:.3}]")
            }
            Some(PointStatistic { mean: Some(mean), .. }) => format!("{mean:.3}"),
            _ => "—".into(),
        };
        let count = self.points.iter().map(|p| p.point + 1).max().unwrap_or(0);
        let mut text = String::new();
        for point in 0..count {
            let Some(first) = self.points.iter().find(|p| p.point == point) else { continue };
            let setting: Vec<String> = (self.parameters.iter().zip(&first.parameters))
                .map(|(path, value)| format!("{path}={value}"))
                .collect();
            text += &format!("point {point} ({}): {} runs ended\n", setting.join(" "), first.runs);
            for name in ["tied_share", "slid_share", "core_speed_cm_s", "core_travel_L"] {
                text += &format!("  {name:<16} {}\n", shown(statistic(point, name)));
            }
        }
        text
    }
}

/// Reads every run of the sweep in `folder` and writes `summary.csv`, `intervals.csv` and
/// `plots/` (module docs).
///
/// # Errors
/// [`CliError`] if the plan, a run's files or an output cannot be read or written.
pub fn collect(folder: &Path) -> Result<Collected, CliError> {
    let plan = Plan::read(folder)?;
    let points = plan.points();
    let mut runs: Vec<Option<RunRow>> = Vec::with_capacity(plan.runs.len());
    for run in &plan.runs {
        let directory = Plan::directory(folder, run);
        let made = directory.join(MANIFEST_FILE).exists() && directory.join("metrics.csv").exists();
        runs.push(if made { Some(RunRow::read(&directory)?) } else { None });
    }
    let prefix = |name: &str| [name.to_owned()].into_iter().chain(plan.parameters.iter().cloned());
    let header: Vec<String> = ["id".to_owned()]
        .into_iter()
        .chain(prefix("point"))
        .chain(["replicate".to_owned()])
        .chain(RunRow::COLUMNS.iter().map(|c| (*c).to_owned()))
        .collect();
    // `replicate` goes after the parameters: the grid point's columns stay together.
    let mut rows = Vec::with_capacity(plan.runs.len());
    for ((run, row), point) in plan.runs.iter().zip(&runs).zip(&points) {
        let values = row.as_ref().map_or_else(missing, RunRow::values);
        let ids = [run.id.clone(), point.to_string()];
        rows.push(
            [ids.to_vec(), plan.values(run), vec![run.replicate.to_string()], values].concat(),
        );
    }
    write_table(&folder.join(SUMMARY_FILE), &header, &rows)?;
    let intervals = point_intervals(&plan, &points, &runs);
    let interval_header: Vec<String> =
        prefix("point").chain(INTERVAL_COLUMNS.iter().map(|c| (*c).to_owned())).collect();
    let interval_rows: Vec<Vec<String>> = intervals.iter().map(PointStatistic::values).collect();
    write_table(&folder.join(INTERVALS_FILE), &interval_header, &interval_rows)?;
    hagfish_report::write_scatters(&scatters(&plan, &runs, &intervals), &folder.join("plots"))?;
    Ok(Collected {
        runs: runs.len(),
        missing: runs.iter().filter(|r| r.is_none()).count(),
        parameters: plan.parameters,
        points: intervals,
    })
}

/// The values of a run not made yet: status `missing`, the rest empty.
fn missing() -> Vec<String> {
    let mut empty = vec![String::new(); RunRow::COLUMNS.len()];
    empty[0] = "missing".into();
    empty
}

/// Writes a CSV table with the `csv` crate's quoting.
fn write_table(path: &Path, header: &[String], rows: &[Vec<String>]) -> Result<(), CliError> {
    let mut text = hagfish_run::csv_record(header);
    for row in rows {
        text.push_str(&hagfish_run::csv_record(row));
    }
    hagfish_run::replace_file(path, text.as_bytes()).map_err(CliError::from)
}

/// One row of `intervals.csv`: a statistic of one grid point.
#[derive(Clone, Debug, PartialEq)]
pub struct PointStatistic {
    /// The grid point's index.
    pub point: usize,
    /// The values of the swept parameters there.
    pub parameters: Vec<String>,
    /// Its ended runs.
    pub runs: usize,
    /// The statistic: a numeric column of [`RunRow`] or a [`Share`]'s name.
    pub statistic: String,
    /// The runs that have a finite value of it (a share: every ended run).
    pub n: usize,
    /// Their mean (a share: the share).
    pub mean: Option<f64>,
    /// Their standard deviation (n − 1 divisor; none for a share or fewer than 2 values).
    pub sd: Option<f64>,
    /// The interval at [`LEVEL`]: bootstrap-t for a mean (none with fewer than
    /// [`MIN_VALUES_FOR_INTERVAL`] values), Wilson for a share.
    pub interval: Option<(f64, f64)>,
}

impl PointStatistic {
    /// Its fields as CSV text (empty where there is none).
    fn values(&self) -> Vec<String> {
        let number = |x: Option<f64>| x.map_or_else(String::new, |x| x.to_string());
        [vec![self.point.to_string()], self.parameters.clone()]
            .concat()
            .into_iter()
            .chain([
                self.runs.to_string(),
                self.statistic.clone(),
                self.n.to_string(),
                number(self.mean),
                number(self.sd),
                number(self.interval.map(|i| i.0)),
                number(self.interval.map(|i| i.1)),
                LEVEL.to_string(),
            ])
            .collect()
    }
}

/// Every grid point's statistics over its ended runs: each numeric column of [`RunRow`], then
/// each [`Share`]. The bootstrap's seed is the point's index and the statistic's, so the table
/// is the same every time it is collected.
fn point_intervals(plan: &Plan, points: &[usize], runs: &[Option<RunRow>]) -> Vec<PointStatistic> {
    let count = points.iter().max().map_or(0, |p| p + 1);
    let mut table = Vec::new();
    for point in 0..count {
        let members: Vec<usize> = (0..points.len()).filter(|&r| points[r] == point).collect();
        let parameters = plan.values(&plan.runs[members[0]]);
        let ended: Vec<&RunRow> = members
            .iter()
            .filter_map(|&r| runs[r].as_ref())
            .filter(|row| ENDED.contains(&row.status.as_str()))
            .collect();
        let numbers: Vec<_> = ended.iter().map(|row| row.numbers()).collect();
        let row = |statistic: &str, n, mean, sd, interval| PointStatistic {
            point,
            parameters: parameters.clone(),
            runs: ended.len(),
            statistic: statistic.to_owned(),
            n,
            mean,
            sd,
            interval,
        };
        for (s, name) in NUMERIC.iter().enumerate() {
            let values: Vec<f64> =
                numbers.iter().filter_map(|v| v[s]).filter(|x| x.is_finite()).collect();
            let seed = ((point as u64) << 16) | s as u64;
            let summary = hagfish_stats::Summary::of(&values);
            let mean = summary.map(|s| s.mean).or_else(|| values.first().copied());
            let interval = (values.len() >= MIN_VALUES_FOR_INTERVAL)
                .then(|| hagfish_stats::mean_interval(&values, LEVEL, RESAMPLES, seed))
                .flatten();
            let bounds = interval.map(|i| (i.low, i.high));
            table.push(row(name, values.len(), mean, summary.map(|s| s.sd), bounds));
        }
        for share in Share::ALL {
            let successes = ended.iter().filter(|r| share.counts(r)).count();
            let n = ended.len();
            let mean = (n > 0).then(|| successes as f64 / n as f64);
            let interval = hagfish_stats::wilson_interval(successes, n, LEVEL);
            table.push(row(share.name(), n, mean, None, interval));
        }
    }
    table
}

/// The numeric columns of [`RunRow`], in its order: those after `status` and `final_knot`.
const NUMERIC: &[&str] = RunRow::COLUMNS.split_at(2).1;

/// Each numeric statistic against each swept parameter whose values are all numbers and not
/// all the same (a scenario override every run shares is a column, not an axis): the runs as
/// points, and each grid point's mean and interval where it has one.
fn scatters(plan: &Plan, runs: &[Option<RunRow>], intervals: &[PointStatistic]) -> Vec<Scatter> {
    let skip = ["steps", "time_s"];
    let mut scatters = Vec::new();
    for (p, parameter) in plan.parameters.iter().enumerate() {
        let x_of = |run: &crate::sweep::PlannedRun| plan.values(run)[p].parse::<f64>().ok();
        let xs: Option<Vec<f64>> = plan.runs.iter().map(x_of).collect();
        if !xs.as_ref().is_some_and(|v| v.iter().any(|x| *x != v[0])) {
            continue;
        }
        let xs = xs.unwrap_or_default();
        for (s, metric) in NUMERIC.iter().enumerate().filter(|(_, m)| !skip.contains(m)) {
            let points: Vec<(f64, f64)> = runs
                .iter()
                .zip(&xs)
                .filter_map(|(row, &x)| Some((x, row.as_ref()?.numbers()[s]?)))
                .collect();
            if points.is_empty() {
                continue;
            }
            let bars = intervals
                .iter()
                .filter(|i| i.statistic == *metric)
                .filter_map(|i| {
                    let (low, high) = i.interval?;
                    let x = i.parameters[p].parse::<f64>().ok()?;
                    Some(IntervalBar { x, mean: i.mean?, low, high })
                })
                .collect();
            scatters.push(Scatter {
                title: format!("{metric} against {parameter}"),
                stem: format!("{}_vs_{}", metric, parameter.replace(['.', '[', ']'], "_")),
                x_label: parameter.clone(),
                y_label: metric.to_string(),
                points,
                intervals: bars,
            });
        }
    }
    scatters
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_numeric_statistics_follow_the_two_text_columns() {
        assert_eq!(&RunRow::COLUMNS[..2], ["status", "final_knot"]);
    }
}
