//! The numbers a parameter study compares across runs, read from a run directory: one
//! [`RunRow`] per run (a row of a sweep's `summary.csv`, `hagfish.Run.summary` in Python).
//!
//! Everything is computed from the files (`manifest.json`, `metrics.csv`, `forces.csv`), so a
//! row describes any run directory, a resumed or an interrupted one included. The knot's
//! numbers follow the knotted core of `metrics.csv` (the shortest knotted stretch of body):
//! - the knot is *tied* at the first frame whose type is the run's final, non-trivial type, and
//!   *held* on the share of the frames from there to the last that show that type;
//! - the core's start when tied is read at the first frame of that type whose core is a
//!   stretch of the body, not all of it (a knot whose shortest knotted stretch is the whole
//!   body has no place yet);
//! - *travel* is how far the core's midpoint moves head-ward from the start of the phase named
//!   `slide` (from the tie if there is none) to its nearest approach to the head while the knot
//!   is of that type (fraction of the body length L; as the acceptance tests of
//!   `tests/integration/tie_family.rs` measure it);
//! - the *speed* is the least-squares slope of the core's midpoint (cm) against time over the
//!   middle 80 % (by time) of the frames of the phase named `slide`, head-ward positive;
//! - the *length change* compares the core's mean length over the first and the last 0.5 s
//!   of that phase (`(last − first) / first`).

use std::path::Path;

use hagfish_report::{Metrics, ThigmoForces};

use crate::CliError;
use crate::manifest::Manifest;

/// The phase whose frames give the slide speed and length change.
pub const SLIDE_PHASE: &str = "slide";

/// Seconds averaged at each end of the slide for its length change.
const LENGTH_WINDOW_S: f64 = 0.5;

/// Share of the slide (by time) cut off at each end before fitting its speed.
const SPEED_TRIM: f64 = 0.1;

/// What one run directory says of its run. Optional numbers are `None` where the run has no
/// such thing (no knot, no slide phase).
#[derive(Clone, Debug, PartialEq)]
pub struct RunRow {
    /// The manifest's status (`completed`, `diverged`, `tie_failed`, `interrupted`, `running`).
    pub status: String,
    /// The knot type of the last frame (`0_1`: none).
    pub final_knot: String,
    /// Its agreement over the closure directions.
    pub knot_agreement: Option<f64>,
    /// Time of the first frame with the final knot type (s).
    pub tied_at_s: Option<f64>,
    /// Share of the frames from that one to the last that show the final knot type.
    pub knot_held_fraction: Option<f64>,
    /// The core's head-ward end at the first frame of the final type whose core is shorter
    /// than the body (fraction of L from the head).
    pub core_start_tied_l: Option<f64>,
    /// Head-ward travel of the core's midpoint from the slide's start (or the tie) to its
    /// nearest approach to the head while the knot was of its final type (L).
    pub core_travel_l: Option<f64>,
    /// The core's head-ward end at the last frame of that type (L from the head).
    pub core_final_start_l: Option<f64>,
    /// Head-ward speed of the core's midpoint over the middle 80 % of the slide (cm/s).
    pub core_speed_cm_s: Option<f64>,
    /// Relative change of the core's length over the slide (0.5 s means at each end).
    pub core_length_change: Option<f64>,
    /// Deepest self penetration over the run, relative to the local radius.
    pub max_self_penetration_rel: f64,
    /// Deepest wall penetration over the run (cm).
    pub max_wall_penetration_cm: f64,
    /// Largest joint-limit excess over the run (°).
    pub max_limit_excess_deg: f64,
    /// Largest |f_thigmo| of any DOF in any frame (dyn·cm).
    pub thigmo_max_dyn_cm: f64,
    /// Mean |f_thigmo| over the DOFs of the frames where it acts (dyn·cm; 0 if it never does).
    pub thigmo_mean_dyn_cm: f64,
    /// Mean |f_thigmo| over the DOFs and the frames of the phase named `slide`: the control
    /// force that slides the knot (dyn·cm; `None` without such a phase).
    pub slide_force_mean_dyn_cm: Option<f64>,
    /// Simulation time reached (s).
    pub time_s: f64,
    /// Steps taken.
    pub steps: u64,
    /// Wall-clock seconds of the run (summed over resumes).
    pub wall_time_s: f64,
}

impl RunRow {
    /// The CSV header of [`RunRow::values`], units in the names.
    pub const COLUMNS: [&'static str; 19] = [
        "status",
        "final_knot",
        "knot_agreement",
        "tied_at_s",
        "knot_held_fraction",
        "core_start_tied_L",
        "core_travel_L",
        "core_final_start_L",
        "core_speed_cm_s",
        "core_length_change_rel",
        "max_self_penetration_rel",
        "max_wall_penetration_cm",
        "max_limit_excess_deg",
        "thigmo_max_dyn_cm",
        "thigmo_mean_dyn_cm",
        "slide_force_mean_dyn_cm",
        "time_s",
        "steps",
        "wall_time_s",
    ];

    /// Reads the row of the run in `directory`.
    ///
    /// # Errors
    /// [`CliError::RunDirectory`] or [`CliError::Report`] if a file is missing or malformed.
    pub fn read(directory: &Path) -> Result<Self, CliError> {
        let manifest = Manifest::read(directory)?;
        let metrics = Metrics::read(&directory.join("metrics.csv"))?;
        let forces = ThigmoForces::read(&directory.join("forces.csv"))?;
        Ok(Self::of(&manifest, &metrics, &forces))
    }

    /// The row of a run with this manifest, metrics and force field.
    pub fn of(manifest: &Manifest, m: &Metrics, forces: &ThigmoForces) -> Self {
        let max = |v: &[f64]| v.iter().fold(0.0, |a: f64, b| a.max(*b));
        let last = m.frames() - 1;
        let knotted = |k: &str| !k.is_empty() && k != "0_1" && !k.starts_with('?');
        let final_knot = m.knot[last].clone();
        let typed: Vec<usize> = if knotted(&final_knot) {
            (0..m.frames()).filter(|&f| m.knot[f] == final_knot).collect()
        } else {
            Vec::new()
        };
        let (tied, untied) = (typed.first().copied(), typed.last().copied());
        let (thigmo_max_dyn_cm, thigmo_mean_dyn_cm) = thigmo_statistics(forces);
        Self {
            status: manifest.status.name().to_owned(),
            knot_agreement: m.knot_agreement[last],
            tied_at_s: tied.map(|f| m.time[f]),
            knot_held_fraction: tied.map(|f| typed.len() as f64 / (last + 1 - f) as f64),
            core_start_tied_l: typed
                .iter()
                .find(|&&f| !core_spans_the_body(m, f))
                .and_then(|&f| m.knot_core_start_l[f]),
            core_travel_l: travel(m, &typed),
            core_final_start_l: untied.and_then(|f| m.knot_core_start_l[f]),
            core_speed_cm_s: slide_speed(m),
            core_length_change: slide_length_change(m),
            final_knot,
            max_self_penetration_rel: max(&m.self_penetration_rel),
            max_wall_penetration_cm: max(&m.wall_penetration),
            max_limit_excess_deg: max(&m.limit_excess_deg),
            thigmo_max_dyn_cm,
            thigmo_mean_dyn_cm,
            slide_force_mean_dyn_cm: slide_force(m, forces),
            time_s: manifest.time_s,
            steps: manifest.steps,
            wall_time_s: manifest.wall_time_s,
        }
    }

    /// The values in the order of [`RunRow::COLUMNS`], as CSV fields (empty for `None`;
    /// numbers with Rust's shortest round-trip formatting).
    pub fn values(&self) -> Vec<String> {
        let number = |x: Option<f64>| x.map_or_else(String::new, |x| x.to_string());
        [self.status.clone(), self.final_knot.clone()]
            .into_iter()
            .chain(self.numbers().into_iter().map(number))
            .collect()
    }

    /// The numeric values, in the order of [`RunRow::COLUMNS`] after its two text columns
    /// (`status`, `final_knot`): what a study averages over replicates.
    pub fn numbers(&self) -> [Option<f64>; Self::COLUMNS.len() - 2] {
        [
            self.knot_agreement,
            self.tied_at_s,
            self.knot_held_fraction,
            self.core_start_tied_l,
            self.core_travel_l,
            self.core_final_start_l,
            self.core_speed_cm_s,
            self.core_length_change,
            Some(self.max_self_penetration_rel),
            Some(self.max_wall_penetration_cm),
            Some(self.max_limit_excess_deg),
            Some(self.thigmo_max_dyn_cm),
            Some(self.thigmo_mean_dyn_cm),
            self.slide_force_mean_dyn_cm,
            Some(self.time_s),
            Some(self.steps as f64),
            Some(self.wall_time_s),
        ]
    }
}

/// Whether frame `f`'s core is the whole body: its head-ward end at the head and its other
/// end, 2·mid − start (fractions of L), at the tail (to 10⁻⁹ L).
fn core_spans_the_body(m: &Metrics, f: usize) -> bool {
    match (m.knot_core_start_l[f], m.knot_core_mid_l[f]) {
        (Some(start), Some(mid)) => start <= 1e-9 && 2.0 * mid - start >= 1.0 - 1e-9,
        _ => false,
    }
}

/// The core's midpoint (cm from the head) of frame `f`, if it has a core.
fn core_mid_cm(m: &Metrics, f: usize) -> Option<f64> {
    Some(0.5 * (m.knot_core_start[f]? + m.knot_core_end[f]?))
}

/// Head-ward travel of the core's midpoint over the `typed` frames (those of the final knot
/// type): from the first of them in the slide (or the first of all) to the smallest midpoint
/// from there on (L).
fn travel(m: &Metrics, typed: &[usize]) -> Option<f64> {
    let start = typed.iter().position(|&f| m.phase[f] == SLIDE_PHASE).unwrap_or(0);
    let mids: Vec<f64> = typed.get(start..)?.iter().filter_map(|&f| m.knot_core_mid_l[f]).collect();
    Some(mids.first()? - mids.iter().fold(f64::INFINITY, |a, &b| a.min(b)))
}

/// The frames of the slide phase that have a core.
fn slide_frames(m: &Metrics) -> Vec<usize> {
    (0..m.frames()).filter(|&f| m.phase[f] == SLIDE_PHASE && core_mid_cm(m, f).is_some()).collect()
}

/// Least-squares slope of the core's midpoint against time over the middle of the slide,
/// head-ward positive (cm/s); `None` with fewer than 3 frames there.
fn slide_speed(m: &Metrics) -> Option<f64> {
    let frames = slide_frames(m);
    let (t0, t1) = (m.time[*frames.first()?], m.time[*frames.last()?]);
    let trim = SPEED_TRIM * (t1 - t0);
    let points: Vec<(f64, f64)> = frames
        .iter()
        .filter(|&&f| m.time[f] >= t0 + trim && m.time[f] <= t1 - trim)
        .filter_map(|&f| Some((m.time[f], core_mid_cm(m, f)?)))
        .collect();
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let (mt, mx) = points.iter().fold((0.0, 0.0), |(a, b), (t, x)| (a + t / n, b + x / n));
    let (stx, stt) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (t, x)| (a + (t - mt) * (x - mx), b + (t - mt) * (t - mt)));
    (stt > 0.0).then(|| -stx / stt)
}

/// `(last − first) / first` of the core's mean length over the first and the last 0.5 s of
/// the slide.
fn slide_length_change(m: &Metrics) -> Option<f64> {
    let frames = slide_frames(m);
    let (t0, t1) = (m.time[*frames.first()?], m.time[*frames.last()?]);
    let mean = |from: f64, to: f64| -> Option<f64> {
        let lengths: Vec<f64> = frames
            .iter()
            .filter(|&&f| m.time[f] >= from && m.time[f] <= to)
            .filter_map(|&f| Some(m.knot_core_end[f]? - m.knot_core_start[f]?))
            .collect();
        (!lengths.is_empty()).then(|| lengths.iter().sum::<f64>() / lengths.len() as f64)
    };
    let first = mean(t0, t0 + LENGTH_WINDOW_S)?;
    let last = mean(t1 - LENGTH_WINDOW_S, t1)?;
    (first > 0.0).then(|| (last - first) / first)
}

/// Mean |f| over the DOFs and the frames of the slide phase (`None` without a slide frame in
/// `forces`).
fn slide_force(m: &Metrics, forces: &ThigmoForces) -> Option<f64> {
    let frames: Vec<usize> = (0..m.frames()).filter(|&f| m.phase[f] == SLIDE_PHASE).collect();
    forces.mean_abs(&frames)
}

/// Largest |f| and mean |f| over the DOFs of the frames where any DOF's force is non-zero.
fn thigmo_statistics(forces: &ThigmoForces) -> (f64, f64) {
    let per_frame = 3 * forces.joints;
    let (mut max, mut sum, mut count) = (0.0_f64, 0.0, 0usize);
    for frame in 0..forces.times.len() {
        let range = frame * forces.joints..(frame + 1) * forces.joints;
        let values = forces.values.iter().flat_map(|axis| axis[range.clone()].iter());
        let frame_sum: f64 = values.clone().map(|f| f.abs()).sum();
        if frame_sum > 0.0 {
            max = values.fold(max, |m, f| m.max(f.abs()));
            sum += frame_sum;
            count += per_frame;
        }
    }
    (max, if count > 0 { sum / count as f64 } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A metrics table of a knot whose core moves from 0.5 L to 0.1 L at 2 cm/s on a 40 cm
    /// body, 0.1 s frames, all in the slide phase.
    fn sliding() -> Metrics {
        let frames = 41;
        let time: Vec<f64> = (0..frames).map(|f| 0.1 * f as f64).collect();
        let mid: Vec<f64> = time.iter().map(|t| 20.0 - 2.0 * t).collect();
        Metrics {
            phase: vec![SLIDE_PHASE.into(); frames],
            knot: vec!["3_1".into(); frames],
            knot_agreement: vec![Some(1.0); frames],
            knot_core_start: mid.iter().map(|x| Some(x - 4.0)).collect(),
            knot_core_end: mid.iter().map(|x| Some(x + 4.0)).collect(),
            knot_core_start_l: mid.iter().map(|x| Some((x - 4.0) / 40.0)).collect(),
            knot_core_mid_l: mid.iter().map(|x| Some(x / 40.0)).collect(),
            self_penetration_rel: vec![0.01; frames],
            wall_penetration: vec![0.0; frames],
            limit_excess_deg: vec![0.0; frames],
            time,
            ..Metrics::default()
        }
    }

    fn manifest() -> Manifest {
        serde_json::from_str(
            r#"{"program":"hagfish","version":"0","scenario":"s.ron","scenario_name":"s",
            "scenario_hash":"0","started_utc":"","ended_utc":null,"status":"completed",
            "wall_time_s":1.5,"steps":400,"frames":41,"time_s":4.0,"final_state_hash":null,
            "error":null,"resumed_at_frames":[],"files":[]}"#,
        )
        .expect("a valid manifest")
    }

    #[test]
    fn a_knot_sliding_at_two_centimetres_a_second_is_measured_so() {
        let none = vec![0.0; 4];
        let forces = ThigmoForces {
            times: vec![0.0, 0.1],
            joints: 2,
            values: [none.clone(), none.clone(), none],
        };
        let row = RunRow::of(&manifest(), &sliding(), &forces);
        assert_eq!(row.final_knot, "3_1");
        assert_eq!(row.tied_at_s, Some(0.0));
        let speed = row.core_speed_cm_s.expect("a slide");
        assert!((speed - 2.0).abs() < 1e-9, "speed {speed}");
        let travel = row.core_travel_l.expect("a knot");
        assert!((travel - 0.2).abs() < 1e-9, "travel {travel}");
        assert!(row.core_length_change.expect("a slide").abs() < 1e-12);
        // Two slide frames of 2 joints × 3 axes, all zero.
        assert_eq!(row.slide_force_mean_dyn_cm, Some(0.0));
        assert_eq!((row.steps, row.status.as_str()), (400, "completed"));
        assert_eq!(row.values().len(), RunRow::COLUMNS.len());
    }

    #[test]
    fn the_tied_core_start_skips_frames_whose_core_is_the_whole_body() {
        let mut m = sliding();
        m.knot[0] = "0_1".into();
        (m.knot_core_start_l[1], m.knot_core_mid_l[1]) = (Some(0.0), Some(0.5));
        m.knot[7] = "0_1".into();
        let forces = ThigmoForces {
            times: vec![0.0],
            joints: 1,
            values: [vec![0.0; 1], vec![0.0; 1], vec![0.0; 1]],
        };
        let row = RunRow::of(&manifest(), &m, &forces);
        assert_eq!(row.tied_at_s, Some(0.1));
        assert_eq!(row.core_start_tied_l, m.knot_core_start_l[2]);
        // Frames 1 … 40 from the tie, one of them (7) without the knot.
        assert_eq!(row.knot_held_fraction, Some(39.0 / 40.0));
    }

    #[test]
    fn a_run_without_a_knot_or_slide_has_no_knot_numbers() {
        let mut m = sliding();
        m.knot = vec!["0_1".into(); m.frames()];
        m.phase = vec!["form".into(); m.frames()];
        let forces = ThigmoForces {
            times: vec![0.0, 0.1],
            joints: 2,
            values: [vec![0.0, 0.0, 3.0, -1.0], vec![0.0; 4], vec![0.0; 4]],
        };
        let row = RunRow::of(&manifest(), &m, &forces);
        assert_eq!((row.tied_at_s, row.core_travel_l, row.core_speed_cm_s), (None, None, None));
        // One acting frame of 2 joints × 3 axes: |3| + |−1| over 6 DOFs.
        assert_eq!((row.thigmo_max_dyn_cm, row.thigmo_mean_dyn_cm), (3.0, 4.0 / 6.0));
        assert_eq!(row.slide_force_mean_dyn_cm, None);
    }
}
