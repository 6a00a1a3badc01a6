//! What one run of a tie → loosen → tighten scenario (`data/scenarios/loosen_tighten.ron`)
//! did to the knot's size, read from its `metrics.csv`: the measures of
//! `tests/integration/knot_size.rs` and of `cargo xtask family --measure loosen-tighten`.

use std::path::Path;

use crate::error::ReportError;
use crate::knot_run::HALF_SECOND_FRAMES;
use crate::metrics_table::{MetricsCsv, first_after_tie, number};

/// The knotted core's length change over the loosen and the tighten phase, whether the knot
/// held, and the deepest penetration.
#[derive(Clone, Debug, PartialEq)]
pub struct LoosenTighten {
    /// The core's length change over the phase named `loosen`: the mean of its last 0.5 s
    /// against the mean of its first 0.5 s. `None` for a phase of less than 1 s (after an
    /// unloosened knot the tighten's end condition holds at once) or without a knotted core
    /// in those frames.
    pub loosen: Option<f64>,
    /// The same over the phase named `tighten`.
    pub tighten: Option<f64>,
    /// The phase of the first frame after tying that does not show the knot (`None`: held on
    /// every frame).
    pub lost_in: Option<String>,
    /// The deepest self penetration of the run (fraction of the local radius).
    pub penetration: f64,
}

/// The fewest frames of a phase whose change is measured (1 s).
const MIN_PHASE_FRAMES: usize = 2 * HALF_SECOND_FRAMES;

impl LoosenTighten {
    /// Reads the run in `dir`, whose tie ties `knot` (its Rolfsen name).
    pub fn read(dir: &Path, knot: &str) -> Result<Self, ReportError> {
        let csv = MetricsCsv::read(dir)?;
        let (phase, shown) = (csv.column("phase")?, csv.column("knot")?);
        let (length, penetration) =
            (csv.column("knot_core_length_cm")?, csv.column("max_self_penetration_rel")?);
        let rows = &csv.rows;
        let change = |name: &str| {
            let frames: Vec<&Vec<String>> = rows.iter().filter(|r| r[phase] == name).collect();
            let mean = |part: &[&Vec<String>]| {
                part.iter().map(|r| number(r, length)).sum::<f64>() / part.len() as f64
            };
            let n = frames.len();
            let change = (n >= MIN_PHASE_FRAMES).then(|| {
                mean(&frames[n - HALF_SECOND_FRAMES..]) / mean(&frames[..HALF_SECOND_FRAMES]) - 1.0
            });
            change.filter(|c| c.is_finite())
        };
        let tied = first_after_tie(rows, phase).ok_or_else(|| csv.unusable("not tied"))?;
        Ok(Self {
            loosen: change("loosen"),
            tighten: change("tighten"),
            lost_in: rows[tied..].iter().find(|r| r[shown] != knot).map(|r| r[phase].clone()),
            penetration: rows.iter().map(|r| number(r, penetration)).fold(0.0, f64::max),
        })
    }

    /// Why this run does not show both effects as its targets' doing, against the control
    /// runs with the loosen's and the tighten's targets at zero (empty: it does): the knot
    /// held on every frame after tying, penetration below 2 % of the radius, the loosen
    /// grows the core by ≥ 25 % and ≥ 20 points more than its control, the tighten shrinks it
    /// by ≥ 25 % and ≥ 20 points more than its control (a control whose knot comes undone
    /// while it should be tightening did not tighten it).
    pub fn failures(&self, loosen_control: &Self, tighten_control: &Self) -> Vec<String> {
        let mut failures = Vec::new();
        let mut fail = |holds: bool, why: String| {
            if !holds {
                failures.push(why);
            }
        };
        fail(self.lost_in.is_none(), format!("the knot was lost in the {:?}", self.lost_in));
        fail(self.penetration < 0.02, format!("penetration {} of r", self.penetration));
        match (self.loosen, loosen_control.loosen) {
            (Some(loosen), Some(control)) => {
                fail(loosen >= 0.25, format!("loosen changed the core by {loosen}"));
                fail(loosen - control >= 0.2, format!("loosen {loosen} against {control}"));
            }
            (loosen, control) => {
                fail(false, format!("no loosen to compare: {loosen:?}, {control:?}"))
            }
        }
        // A control whose knot comes undone while it should be tightening did not tighten it.
        let control_undone = tighten_control.lost_in.as_deref() == Some("tighten");
        match (self.tighten, tighten_control.tighten) {
            (None, _) => fail(false, "no tighten (shorter than 1 s or unknotted)".into()),
            (Some(tighten), control) => {
                fail(tighten <= -0.25, format!("tighten changed the core by {tighten}"));
                match control {
                    _ if control_undone => {}
                    Some(control) => {
                        fail(
                            control - tighten >= 0.2,
                            format!("tighten {tighten} against {control}"),
                        );
                    }
                    None => fail(false, "no tighten in the control to compare".into()),
                }
            }
        }
        failures
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sizes(loosen: f64, tighten: f64, lost_in: Option<&str>) -> LoosenTighten {
        LoosenTighten {
            loosen: Some(loosen),
            tighten: Some(tighten),
            lost_in: lost_in.map(str::to_owned),
            penetration: 0.01,
        }
    }

    #[test]
    fn both_effects_count_only_past_their_controls() {
        let run = sizes(0.32, -0.30, None);
        assert!(run.failures(&sizes(-0.02, 0.0, None), &sizes(0.3, 0.06, None)).is_empty());
        // 19.98 points past the loosen's control: short of 20.
        let failures = run.failures(&sizes(0.1202, 0.0, None), &sizes(0.3, 0.06, None));
        assert_eq!(failures.len(), 1, "{failures:?}");
        // A tighten control that loses its knot while tightening did not tighten it.
        let undone = LoosenTighten { tighten: None, ..sizes(0.3, 0.0, Some("tighten")) };
        assert!(run.failures(&sizes(0.0, 0.0, None), &undone).is_empty());
        let lost = sizes(0.32, -0.30, Some("loosen"));
        assert_eq!(lost.failures(&sizes(0.0, 0.0, None), &sizes(0.3, 0.06, None)).len(), 1);
    }
}
