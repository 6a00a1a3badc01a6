//! How each metric is compared with its golden, and why that tolerance.
//!
//! A bless runs every scenario as written and with its time step changed by a few parts in
//! 10¹² ([`PERTURBATIONS`]): rounding-level perturbations, like another CPU's SIMD width or a
//! reordered sum. The largest change of each metric over those runs is its measured *spread*,
//! kept in the golden. A check accepts a metric within [`SPREAD_FACTOR`] spreads of the golden
//! (plus 1e-9 of its magnitude, for metrics that rounding does not move at all), so each
//! tolerance is as wide as rounding makes that metric move in that scenario, and no wider: a
//! small metric is not checked to ±100 % as a fixed relative rule with a floor would do.
//! The step count is a number like the others (exact where rounding does not move it: a run of
//! fixed duration); the final-state digest is exact on the blessed platform only.

use crate::metrics::{Value, parse_runs};

/// Relative changes of the time step of the perturbed runs of a bless.
pub const PERTURBATIONS: [f64; 4] = [1e-12, 2e-12, 3e-12, 4e-12];

/// Tolerance in measured spreads: the worst of four perturbed runs underestimates the spread of
/// rounding, and three times it still rejects a change of behaviour (another knot, a knot
/// centimetres elsewhere) wherever rounding alone moves a metric much less than that change.
pub const SPREAD_FACTOR: f64 = 3.0;

/// Below this many frames of difference a knot sequence passes even with a zero spread: a
/// one-frame shift of a knot's appearance is the resolution of the 0.1 s recording.
const MIN_FRAME_BOUND: usize = 2;

/// The rule of one metric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// Equal values (text or number).
    Exact,
    /// |now − golden| ≤ the bound.
    Absolute(f64),
    /// Run-length encoded knot names: the same names in the same order, each run's frame
    /// count within the bound.
    Runs(usize),
    /// The final-state digest: exact on the blessed platform, not compared elsewhere.
    Digest,
}

/// The spread of a metric over perturbed runs: the largest |perturbed − golden| for numbers,
/// the largest difference of a knot run's frame count for knot sequences, 0 for values that
/// are missing in every run or for the digest (compared on the blessed platform only). The
/// step count is a number like the others: exact (spread 0) for a run of fixed duration, and
/// spread over the perturbed runs where the run ends with its phases (`end_after_phases`).
///
/// # Errors
/// A perturbed run whose value is of another kind (a number where the golden has none) or
/// whose knot sequence has other names: the scenario's behaviour depends on rounding, which
/// no tolerance can accept honestly.
pub fn spread(name: &str, golden: &Value, perturbed: &[Value]) -> Result<f64, String> {
    if name == "digest" {
        return Ok(0.0);
    }
    let mut worst = 0.0_f64;
    for value in perturbed {
        let change = match (golden, value) {
            (Value::Missing, Value::Missing) => 0.0,
            (Value::Number(g), Value::Number(n)) => (n - g).abs(),
            (Value::Text(g), Value::Text(n)) => match (parse_runs(g), parse_runs(n)) {
                (Some(g), Some(n))
                    if g.len() == n.len() && g.iter().zip(&n).all(|(a, b)| a.0 == b.0) =>
                {
                    g.iter().zip(&n).map(|(a, b)| a.1.abs_diff(b.1)).max().unwrap_or(0) as f64
                }
                _ => return Err(format!("{name}: {g} as written, {n} under rounding")),
            },
            (g, n) => return Err(format!("{name}: {g:?} as written, {n:?} under rounding")),
        };
        worst = worst.max(change);
    }
    Ok(worst)
}

/// The tolerance of metric `name` (names of `metrics::METRIC_NAMES`) with blessed value
/// `golden` and measured `spread`.
pub fn tolerance(name: &str, golden: &Value, spread: f64) -> Tolerance {
    match (name, golden) {
        ("digest", _) => Tolerance::Digest,
        ("knots", _) => {
            Tolerance::Runs(((SPREAD_FACTOR * spread).ceil() as usize).max(MIN_FRAME_BOUND))
        }
        (_, Value::Number(g)) => Tolerance::Absolute(SPREAD_FACTOR * spread + 1e-9 * g.abs()),
        _ => Tolerance::Exact,
    }
}

impl Tolerance {
    /// Short description for the table.
    pub fn describe(&self) -> String {
        match self {
            Tolerance::Exact => "exact".into(),
            Tolerance::Absolute(bound) => format!("±{bound:.3e}"),
            Tolerance::Runs(frames) => format!("runs ±{frames}"),
            Tolerance::Digest => "same platform".into(),
        }
    }

    /// Whether `now` passes against `golden`; `same_platform` decides whether a digest
    /// counts. `None`: not compared (a digest from another platform).
    pub fn accepts(&self, golden: &Value, now: &Value, same_platform: bool) -> Option<bool> {
        use Value::{Missing, Number, Text};
        Some(match (self, golden, now) {
            (Tolerance::Digest, _, _) if !same_platform => return None,
            (_, Missing, Missing) => true,
            (Tolerance::Absolute(bound), Number(g), Number(n)) => (n - g).abs() <= *bound,
            (Tolerance::Runs(frames), Text(g), Text(n)) => match (parse_runs(g), parse_runs(n)) {
                (Some(g), Some(n)) => {
                    g.len() == n.len()
                        && g.iter()
                            .zip(&n)
                            .all(|((gn, gc), (nn, nc))| gn == nn && gc.abs_diff(*nc) <= *frames)
                }
                _ => false,
            },
            (Tolerance::Exact | Tolerance::Digest, g, n) => g == n,
            _ => false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Value::{Missing, Number, Text};

    #[test]
    fn numbers_pass_within_and_fail_outside_their_bounds() {
        let absolute = Tolerance::Absolute(1.0);
        assert_eq!(absolute.accepts(&Number(2.0), &Number(2.9), true), Some(true));
        assert_eq!(absolute.accepts(&Number(2.0), &Number(3.1), true), Some(false));
        assert_eq!(absolute.accepts(&Number(2.0), &Missing, true), Some(false));
    }

    #[test]
    fn tolerances_scale_with_the_measured_spread() {
        let golden = Number(0.08);
        let spread = spread("mean", &golden, &[Number(0.081), Number(0.0795)]).expect("spread");
        assert!((spread - 0.001).abs() < 1e-15);
        let rule = tolerance("mean", &golden, spread);
        assert_eq!(rule.accepts(&golden, &Number(0.0829), true), Some(true));
        // A small metric is not checked to ±100 %: 0.16 is twice the golden and fails.
        assert_eq!(rule.accepts(&golden, &Number(0.16), true), Some(false));
        // A metric that rounding does not move is checked to 1e-9 of its size.
        let still = tolerance("mean", &golden, 0.0);
        assert_eq!(still.accepts(&golden, &Number(0.08 * (1.0 + 1e-10)), true), Some(true));
        assert_eq!(still.accepts(&golden, &Number(0.08 * (1.0 + 1e-8)), true), Some(false));
    }

    #[test]
    fn a_knot_sequence_that_rounding_changes_has_no_spread() {
        let golden = Text("0_1*100 3_1*201".into());
        let shifted = Text("0_1*104 3_1*197".into());
        assert_eq!(spread("knots", &golden, std::slice::from_ref(&shifted)), Ok(4.0));
        assert!(spread("knots", &golden, &[Text("0_1*301".into())]).is_err());
        assert!(spread("knot_speed_cm_s", &Number(1.0), &[Missing]).is_err());
        assert_eq!(tolerance("knots", &golden, 4.0), Tolerance::Runs(12));
        assert_eq!(tolerance("knots", &golden, 0.0), Tolerance::Runs(MIN_FRAME_BOUND));
    }

    #[test]
    fn knot_runs_need_the_same_names_and_close_counts() {
        let runs = Tolerance::Runs(10);
        let golden = Text("0_1*100 3_1*201".into());
        assert_eq!(runs.accepts(&golden, &Text("0_1*108 3_1*193".into()), true), Some(true));
        assert_eq!(runs.accepts(&golden, &Text("0_1*120 3_1*181".into()), true), Some(false));
        assert_eq!(runs.accepts(&golden, &Text("0_1*301".into()), true), Some(false));
        assert_eq!(runs.accepts(&golden, &Text("0_1*100 4_1*201".into()), true), Some(false));
    }

    #[test]
    fn the_step_count_is_exact_unless_the_run_ends_with_its_phases() {
        let fixed = tolerance("steps", &Number(3000.0), 0.0);
        assert_eq!(fixed.accepts(&Number(3000.0), &Number(3000.0), true), Some(true));
        assert_eq!(fixed.accepts(&Number(3000.0), &Number(3001.0), true), Some(false));
        let golden = Number(2471.0);
        let spread = spread("steps", &golden, &[Number(2441.0), Number(2421.0)]).expect("spread");
        let ended = tolerance("steps", &golden, spread);
        assert_eq!(ended.accepts(&golden, &Number(2400.0), true), Some(true));
        assert_eq!(ended.accepts(&golden, &Number(2300.0), true), Some(false));
    }

    #[test]
    fn digest_counts_only_on_the_blessed_platform() {
        let (a, b) = (Text("00ff".into()), Text("00fe".into()));
        assert_eq!(Tolerance::Digest.accepts(&a, &b, true), Some(false));
        assert_eq!(Tolerance::Digest.accepts(&a, &a, true), Some(true));
        assert_eq!(Tolerance::Digest.accepts(&a, &b, false), None);
    }
}
