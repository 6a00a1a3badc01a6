//! What one run of a tie → loosen → tighten scenario (`data/scenarios/loosen_tighten.ron`)
//! did to the knot's size, read from its `metrics.csv`: the measures of `tests/knot_size.rs`
//! and of `cargo xtask family --measure loosen-tighten`.

use std::path::Path;

use crate::knot_run::HALF_SECOND_FRAMES;
use crate::metrics_csv::{MetricsCsv, first_after_tie, number};

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
    pub fn read(dir: &Path, knot: &str) -> Result<Self, String> {
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
        let tied = first_after_tie(rows, phase).ok_or("not tied")?;
        Ok(Self {
            loosen: change("loosen"),
            tighten: change("tighten"),
            lost_in: rows[tied..].iter().find(|r| r[shown] != knot).map(|r| r[phase].clone()),
            penetration: rows.iter().map(|r| number(r, penetration)).fold(0.0, f64::max),
        })
    }
}
