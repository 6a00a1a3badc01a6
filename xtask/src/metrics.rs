//! The metrics of one scenario run, computed from its recorded frames and final state.
//!
//! Every metric is a named [`Value`] in a fixed order; `tolerance.rs` says how each is
//! compared. "Knotted frames" are the frames whose knot analysis found a knot with a
//! position (a non-trivial type); travels and speeds run from the first to the last of them.

use hagfish_run::{Frame, FrameSink, RunError, RunSummary};
use hagfish_sim::state_hash;
use hagfish_tree::State;
use serde::{Deserialize, Serialize};

/// One metric's value.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Value {
    /// A number (units in the metric's name).
    Number(f64),
    /// Text: the run-length encoded knot sequence or the digest.
    Text(String),
    /// Not defined in this run (e.g. a speed without knotted frames).
    Missing,
}

/// What the regression keeps of one frame.
#[derive(Clone, Debug)]
struct FrameSample {
    time: f64,
    /// Knot type name (`0_1`, `3_1`, …), `-` if the analysis failed.
    knot: String,
    /// Knot position along the body (cm), for a knotted frame.
    knot_position: Option<f64>,
    /// Arc length of the first (most anterior) self contact (cm).
    first_contact: Option<f64>,
    /// Length of the stretch the self contacts span (cm).
    span: Option<f64>,
    /// max |f| over the DOFs of the thigmotaxis group (dyn·cm).
    max_thigmo: f64,
    /// Euclidean norm of the summed recorded constraint forces (dyn·cm).
    force_norm: f64,
}

/// A [`FrameSink`] keeping the samples the metrics need.
#[derive(Default)]
pub struct Samples(Vec<FrameSample>);

impl FrameSink for Samples {
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), RunError> {
        let groups = &frame.forces.values;
        let thigmo = &groups[2];
        let dofs = groups.iter().map(Vec::len).max().unwrap_or(0);
        let force_norm = (0..dofs)
            .map(|a| groups.iter().filter_map(|g| g.get(a)).sum::<f64>().powi(2))
            .sum::<f64>()
            .sqrt();
        self.0.push(FrameSample {
            time: frame.time,
            knot: frame.knot.map_or_else(|| "-".to_owned(), |k| k.knot.to_string()),
            knot_position: frame.knot.and_then(|k| k.position),
            first_contact: frame.span.map(|s| s.first_contact_cm),
            span: frame.span.map(|s| s.length_cm()),
            max_thigmo: thigmo.iter().fold(0.0, |m: f64, f| m.max(f.abs())),
            force_norm,
        });
        Ok(())
    }
}

/// Names of the metrics, in table order.
pub const METRIC_NAMES: [&str; 14] = [
    "knots",
    "knot_travel_cm",
    "knot_speed_cm_s",
    "first_contact_travel_cm",
    "first_contact_speed_cm_s",
    "span_change_cm",
    "max_penetration_rel",
    "max_thigmo_dyn_cm",
    "mean_force_q1_dyn_cm",
    "mean_force_q2_dyn_cm",
    "mean_force_q3_dyn_cm",
    "mean_force_q4_dyn_cm",
    "steps",
    "digest",
];

/// The metrics of a run: `(name, value)` in the order of [`METRIC_NAMES`].
pub fn metrics(samples: &Samples, summary: &RunSummary, end: &State) -> Vec<(String, Value)> {
    let frames = &samples.0;
    let knotted: Vec<&FrameSample> = frames.iter().filter(|f| f.knot_position.is_some()).collect();
    let travel = |value: fn(&FrameSample) -> Option<f64>| {
        let with: Vec<(f64, f64)> =
            knotted.iter().filter_map(|f| Some((f.time, value(f)?))).collect();
        let (first, last) = (with.first()?, with.last()?);
        if with.len() < 2 {
            return None;
        }
        Some((last.1 - first.1, (last.1 - first.1) / (last.0 - first.0)))
    };
    let knot = travel(|f| f.knot_position);
    let contact = travel(|f| f.first_contact);
    let span = travel(|f| f.span);
    let number = |v: Option<f64>| v.map_or(Value::Missing, Value::Number);
    let quarters = quarter_means(frames);
    let values = [
        Value::Text(run_length_encode(frames.iter().map(|f| f.knot.as_str()))),
        number(knot.map(|k| k.0)),
        number(knot.map(|k| k.1)),
        number(contact.map(|c| c.0)),
        number(contact.map(|c| c.1)),
        number(span.map(|s| s.0)),
        Value::Number(summary.maxima.self_penetration_relative),
        Value::Number(frames.iter().fold(0.0, |m: f64, f| m.max(f.max_thigmo))),
        number(quarters[0]),
        number(quarters[1]),
        number(quarters[2]),
        number(quarters[3]),
        Value::Number(summary.steps as f64),
        Value::Text(state_hash(end)),
    ];
    METRIC_NAMES.iter().map(|n| n.to_string()).zip(values).collect()
}

/// Mean force norm over the frames of each quarter of the run's duration (frame 0 excluded:
/// no step has ended there).
fn quarter_means(frames: &[FrameSample]) -> [Option<f64>; 4] {
    let end = frames.last().map_or(0.0, |f| f.time);
    let mut sums = [(0.0, 0usize); 4];
    for frame in frames.iter().skip(1) {
        let quarter = ((4.0 * frame.time / end).ceil() as usize).clamp(1, 4) - 1;
        sums[quarter].0 += frame.force_norm;
        sums[quarter].1 += 1;
    }
    sums.map(|(sum, n)| (n > 0).then(|| sum / n as f64))
}

/// `3_1*12 0_1*3`: each distinct consecutive knot name with the number of frames it lasts.
pub fn run_length_encode<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let mut runs: Vec<(&str, usize)> = Vec::new();
    for name in names {
        match runs.last_mut() {
            Some((last, count)) if *last == name => *count += 1,
            _ => runs.push((name, 1)),
        }
    }
    runs.iter().map(|(name, count)| format!("{name}*{count}")).collect::<Vec<_>>().join(" ")
}

/// Parses [`run_length_encode`]'s output back into runs, or `None` if malformed.
pub fn parse_runs(text: &str) -> Option<Vec<(&str, usize)>> {
    text.split_whitespace()
        .map(|run| {
            let (name, count) = run.rsplit_once('*')?;
            Some((name, count.parse().ok()?))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn run_length_encoding_round_trips() {
        let names = ["0_1", "0_1", "-", "3_1", "3_1", "3_1"];
        let text = run_length_encode(names.into_iter());
        assert_eq!(text, "0_1*2 -*1 3_1*3");
        assert_eq!(parse_runs(&text), Some(vec![("0_1", 2), ("-", 1), ("3_1", 3)]));
        assert_eq!(parse_runs("3_1*x"), None);
    }
}
