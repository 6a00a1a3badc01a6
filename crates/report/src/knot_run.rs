//! What one run of a tie → tighten → slide scenario did, read from the `metrics.csv` of its
//! run directory: the measures of the knot tables of `docs/physics.md`, asserted on by
//! `tests/integration/tie_family.rs` and tabulated by `cargo xtask family`.

use std::path::Path;

use crate::error::ReportError;
use crate::metrics_table::{MetricsCsv, first_after_tie, number};

/// The measures of one run (fractions of the body length L unless stated).
#[derive(Clone, Debug, PartialEq)]
pub struct KnotRun {
    /// The knot type and the core's writhe of every frame after tying.
    pub after_tying: Vec<(String, f64)>,
    /// The first frame after the tie phase (s).
    pub tied_s: f64,
    /// The core's head-ward end in that frame.
    pub tied_core_start: f64,
    /// The slide phase's first and last frames (s).
    pub slide_s: (f64, f64),
    /// The core midpoint's travel toward the head during the slide: from the slide's first
    /// frame to its nearest in the slide (a passive drift after the slide does not count).
    pub travel: f64,
    /// The core's nearest head-ward end during the slide.
    pub nearest: f64,
    /// The core's length change over the slide: the mean of its last 0.5 s against the mean
    /// of its first 0.5 s (single frames jump by ±15 % as the core's ends move by a body).
    pub change: f64,
    /// The midpoint's speed toward the head over the middle 80 % of the slide's frames (cm/s):
    /// the least-squares slope (the difference of two single frames carries the core's
    /// frame-to-frame noise: 1.38 against 2.22 cm/s on the two mirror-image ES103 runs, 1.87
    /// against 1.93 fitted; docs/physics.md).
    pub speed: f64,
    /// The deepest self penetration of the run (fraction of the local radius; of the cores
    /// for a body with a skin).
    pub penetration: f64,
    /// The deepest compression of the skins in the run (fraction of their thickness; 0
    /// without a skin).
    pub skin_compression: f64,
    /// The largest joint-limit excess of the run (deg).
    pub limit_excess_deg: f64,
}

/// Frames of 0.1 s in half a second: the means of [`KnotRun::change`] and
/// [`crate::LoosenTighten`].
pub(crate) const HALF_SECOND_FRAMES: usize = 5;
/// Fewest slide frames for the measures to mean anything.
const MIN_SLIDE_FRAMES: usize = 10;

/// The Markdown header of [`KnotRun::table_row`]'s table.
pub const TABLE_HEADER: &str = "| variant | tied at (s) | held | core start when tied (L) | \
     slide (s) | travel (L) | nearest core end (L) | core length change | speed (cm/s) | \
     max penetration (% r) | max skin compression (%) |\n|---|---|---|---|---|---|---|---|---|---|---|";

/// The bounds a tie → tighten → slide run is judged by (fractions of the body length L): the
/// trefoil's of the family table and of issue #37's k-mode slides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlideBounds {
    /// Whose bounds they are, for messages ("the trefoil's").
    pub name: &'static str,
    /// Least share of the frames after tying that show the knot (of its handedness).
    pub held: f64,
    /// Least head-ward end of the core when tied.
    pub tied_core_start: f64,
    /// Least travel of the core's midpoint toward the head.
    pub travel: f64,
    /// Largest nearest head-ward end of the core in the slide.
    pub nearest: f64,
    /// The speed asked (cm/s) and the relative band around it, `|v/v₀ − 1| ≤ band`; `None`
    /// judges no speed.
    pub speed: Option<(f64, f64)>,
    /// Largest self penetration (fraction of the local radius, of the cores with a skin).
    pub penetration: f64,
    /// Largest joint-limit excess (deg).
    pub limit_excess_deg: f64,
}

impl SlideBounds {
    /// The trefoil's bounds: held ≥ 99 %, tied ≥ 0.35 L from the head, travel ≥ 0.25 L, to
    /// ≤ 0.05 L of the head, 2 cm/s ± 30 %, penetration < 2 % of r, limit excess < 0.5°.
    pub const TREFOIL: Self = Self {
        name: "the trefoil's",
        held: 0.99,
        tied_core_start: 0.35,
        travel: 0.25,
        nearest: 0.05,
        speed: Some((2.0, 0.3)),
        penetration: 0.02,
        limit_excess_deg: 0.5,
    };

    /// The Miller Institute knot's bounds (issue #36): shown on ≥ 95 % of the frames after
    /// tying, tied ≥ 0.2 L from the head, travel ≥ 0.15 L, to ≤ 0.05 L of the head, no speed
    /// asked, core penetration < 2 % of r, limit excess < 0.5°.
    pub const MILLER_INSTITUTE: Self = Self {
        name: "the Miller Institute knot's",
        held: 0.95,
        tied_core_start: 0.2,
        travel: 0.15,
        nearest: 0.05,
        speed: None,
        penetration: 0.02,
        limit_excess_deg: 0.5,
    };

    /// The bounds a knot of Rolfsen name `knot` is judged by: 6_2's for 6_2, the trefoil's
    /// for any other (the figure-eight is asked to meet them).
    pub fn for_knot(knot: &str) -> Self {
        if knot == "6_2" { Self::MILLER_INSTITUTE } else { Self::TREFOIL }
    }
}

impl std::fmt::Display for SlideBounds {
    /// "the trefoil's slide bounds (held ≥ 99 %, tied ≥ 0.35 L, …)".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} slide bounds (held ≥ {} %, tied ≥ {} L, travel ≥ {} L, to ≤ {} L",
            self.name,
            self.held * 100.0,
            self.tied_core_start,
            self.travel,
            self.nearest
        )?;
        if let Some((speed, band)) = self.speed {
            write!(f, ", {speed} cm/s ± {} %", band * 100.0)?;
        }
        write!(
            f,
            ", penetration < {} %, limit excess < {}°)",
            self.penetration * 100.0,
            self.limit_excess_deg
        )
    }
}

impl KnotRun {
    /// Reads the run in `dir`, or says why it has no such measures (no file, not tied, too
    /// short a slide).
    pub fn read(dir: &Path) -> Result<Self, ReportError> {
        let csv = MetricsCsv::read(dir)?;
        let (phase, knot, writhe) =
            (csv.column("phase")?, csv.column("knot")?, csv.column("knot_writhe")?);
        let (time, start, mid) = (
            csv.column("time_s")?,
            csv.column("knot_core_start_L")?,
            csv.column("knot_core_mid_L")?,
        );
        let (length_cm, length_l) =
            (csv.column("knot_core_length_cm")?, csv.column("knot_core_length_L")?);
        let (penetration, excess, skin) = (
            csv.column("max_self_penetration_rel")?,
            csv.column("max_limit_excess_deg")?,
            csv.column("max_skin_compression")?,
        );
        let rows = &csv.rows;
        let tied = first_after_tie(rows, phase).ok_or_else(|| csv.unusable("not tied"))?;
        let after = &rows[tied..];
        let slide: Vec<&Vec<String>> = rows.iter().filter(|r| r[phase] == "slide").collect();
        if slide.len() < MIN_SLIDE_FRAMES {
            return Err(csv.unusable(format!("{} slide frames", slide.len())));
        }
        // The body length, from the core's length in cm and in L.
        let body_cm = number(&rows[tied], length_cm) / number(&rows[tied], length_l);
        let half_second = |frames: &[&Vec<String>]| {
            frames.iter().map(|r| number(r, length_cm)).sum::<f64>() / frames.len() as f64
        };
        let middle = &slide[slide.len() / 10..slide.len() * 9 / 10];
        let path: Vec<(f64, f64)> =
            middle.iter().map(|r| (number(r, time), number(r, mid) * body_cm)).collect();
        let maximum = |k: usize| rows.iter().map(|r| number(r, k)).fold(0.0, f64::max);
        let last = slide.len() - 1;
        Ok(Self {
            after_tying: after.iter().map(|r| (r[knot].clone(), number(r, writhe))).collect(),
            tied_s: number(&rows[tied], time),
            tied_core_start: number(&rows[tied], start),
            slide_s: (number(slide[0], time), number(slide[last], time)),
            travel: number(slide[0], mid)
                - slide.iter().map(|r| number(r, mid)).fold(f64::INFINITY, f64::min),
            nearest: slide.iter().map(|r| number(r, start)).fold(1.0, f64::min),
            change: half_second(&slide[slide.len() - HALF_SECOND_FRAMES..])
                / half_second(&slide[..HALF_SECOND_FRAMES])
                - 1.0,
            speed: -slope(&path),
            penetration: maximum(penetration),
            skin_compression: maximum(skin),
            limit_excess_deg: maximum(excess),
        })
    }

    /// The fraction of the frames after tying that show `knot`, and with `writhe_sign` its
    /// handedness (writhe of that sign, beyond 0.5).
    pub fn held(&self, knot: &str, writhe_sign: Option<f64>) -> f64 {
        let shown = self.after_tying.iter().filter(|(name, writhe)| {
            name == knot && writhe_sign.is_none_or(|sign| sign * writhe > 0.5)
        });
        shown.count() as f64 / self.after_tying.len() as f64
    }

    /// The bounds of `bounds` this run misses, each said with its measure (empty: it passes);
    /// `knot` and `writhe_sign` as in [`KnotRun::held`].
    pub fn failures(
        &self,
        bounds: &SlideBounds,
        knot: &str,
        writhe_sign: Option<f64>,
    ) -> Vec<String> {
        let held = self.held(knot, writhe_sign);
        let speed_ok = bounds.speed.is_none_or(|(v, band)| (self.speed / v - 1.0).abs() <= band);
        let checks = [
            (
                held >= bounds.held,
                format!("held on {:.1} % of the frames after tying", 100.0 * held),
            ),
            (
                self.tied_core_start >= bounds.tied_core_start,
                format!("core's head-ward end at {:.3} L when tied", self.tied_core_start),
            ),
            (
                self.travel >= bounds.travel,
                format!("the core's midpoint moved {:.3} L", self.travel),
            ),
            (
                self.nearest <= bounds.nearest,
                format!("the core's head-ward end came to {:.3} L", self.nearest),
            ),
            (speed_ok, format!("{:.2} cm/s", self.speed)),
            (
                self.penetration < bounds.penetration,
                format!("self penetration {:.2} % of r", 100.0 * self.penetration),
            ),
            (
                self.limit_excess_deg < bounds.limit_excess_deg,
                format!("limit excess {:.2}°", self.limit_excess_deg),
            ),
        ];
        checks.into_iter().filter(|(ok, _)| !ok).map(|(_, why)| why).collect()
    }

    /// This run as a row of the table under [`TABLE_HEADER`], `held` as in [`KnotRun::held`].
    pub fn table_row(&self, name: &str, knot: &str, writhe_sign: Option<f64>) -> String {
        format!(
            "| {name} | {:.1} | {:.0} % | {:.3} | {:.1}–{:.1} | {:.3} | {:.3} | {} | {:.2} | \
             {:.2} | {:.0} |",
            self.tied_s,
            100.0 * self.held(knot, writhe_sign),
            self.tied_core_start,
            self.slide_s.0,
            self.slide_s.1,
            self.travel,
            self.nearest,
            signed_percent(self.change),
            self.speed,
            100.0 * self.penetration,
            100.0 * self.skin_compression,
        )
    }
}

/// A change as a signed whole percentage, "+26 %", "−4 %", "0 %" when it rounds to zero,
/// "—" when it is not a number.
pub fn signed_percent(change: f64) -> String {
    let percent = (100.0 * change).round();
    if !percent.is_finite() {
        "—".into()
    } else if percent == 0.0 {
        "0 %".into()
    } else if percent > 0.0 {
        format!("+{percent} %")
    } else {
        format!("−{} %", -percent)
    }
}

/// The least-squares slope of `points` (x, y).
fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (mx, my) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let covariance: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let variance: f64 = points.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    covariance / variance
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A metrics.csv of a knot tied at 1.0 s and slid from 2.0 s at 1 cm/s on a 10 cm body,
    /// its core 4 cm long throughout.
    fn metrics() -> String {
        let mut text = String::from(
            "time_s,phase,knot,knot_writhe,knot_core_start_L,knot_core_mid_L,\
             knot_core_length_cm,knot_core_length_L,max_self_penetration_rel,\
             max_limit_excess_deg,max_skin_compression\n",
        );
        for k in 0..=40 {
            let t = 0.1 * f64::from(k);
            let phase = if t < 0.95 {
                "tie"
            } else if t < 1.95 {
                "tighten"
            } else {
                "slide"
            };
            let start = if t < 1.95 { 0.5 } else { 0.5 - 0.1 * (t - 2.0) };
            text += &format!("{t},{phase},3_1,2.0,{start},{},4.0,0.4,0.01,0.0,0.5\n", start + 0.2);
        }
        text
    }

    #[test]
    fn a_steady_slide_is_read_as_its_speed_travel_and_times() {
        let dir = std::env::temp_dir().join(format!("hagfish-knot-run-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a directory");
        std::fs::write(dir.join("metrics.csv"), metrics()).expect("write");
        let run = KnotRun::read(&dir);
        std::fs::remove_dir_all(&dir).expect("remove");
        let run = run.expect("measured");
        assert_eq!((run.tied_s, run.slide_s), (1.0, (2.0, 4.0)));
        assert!((run.speed - 1.0).abs() < 1e-9, "1 cm/s: {}", run.speed);
        assert!((run.travel - 0.2).abs() < 1e-9, "0.2 L: {}", run.travel);
        assert!((run.nearest - 0.3).abs() < 1e-9 && run.change.abs() < 1e-12);
        assert_eq!(run.held("3_1", Some(1.0)), 1.0);
        assert_eq!(run.held("3_1", Some(-1.0)), 0.0);
        let row = run.table_row("test", "3_1", None);
        assert_eq!(
            row,
            "| test | 1.0 | 100 % | 0.500 | 2.0–4.0 | 0.200 | 0.300 | 0 % | 1.00 | 1.00 | 50 |"
        );
        let failures = run.failures(&SlideBounds::TREFOIL, "3_1", Some(1.0));
        assert_eq!(
            failures,
            [
                "the core's midpoint moved 0.200 L",
                "the core's head-ward end came to 0.300 L",
                "1.00 cm/s"
            ]
        );
        assert_eq!(
            SlideBounds::TREFOIL.to_string(),
            "the trefoil's slide bounds (held ≥ 99 %, tied ≥ 0.35 L, travel ≥ 0.25 L, to ≤ 0.05 L, \
             2 cm/s ± 30 %, penetration < 2 %, limit excess < 0.5°)"
        );
        let lenient = SlideBounds {
            travel: 0.19,
            nearest: 0.31,
            speed: Some((1.0, 0.01)),
            ..SlideBounds::TREFOIL
        };
        assert_eq!(run.failures(&lenient, "3_1", Some(1.0)), Vec::<String>::new());
        assert_eq!(run.failures(&lenient, "3_1", Some(-1.0)).len(), 1, "the mirror image");
        let signed = [0.26, -0.04, -0.004, f64::NAN].map(signed_percent);
        assert_eq!(signed, ["+26 %", "−4 %", "0 %", "—"].map(String::from));
    }
}
