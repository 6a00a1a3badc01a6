//! How a knot tied around a still cylinder sat on it and moved along it in the slide, read
//! from a run's `metrics.csv`, `centreline.csv` and `forces.csv`: the measures of
//! `tests/integration/around_cylinder.rs` and of `cargo xtask family --measure cylinder`
//! (`data/scenarios/pole.ron`; docs/physics.md, "A knot around a pole").
//!
//! - **Around it.** The knotted core (the body centres from `knot_first_body` to
//!   `knot_last_body`), closed by the chord from its last centre back to its first, winds
//!   about the cylinder's axis w = (1/2π) Σ Δφ times, φ the angle of a centre about the axis
//!   in the plane normal to it: an integer for a closed curve that does not touch the axis.
//!   |w| ≥ 1 means the core encircles the cylinder; a knot tied beside it has w = 0.
//! - **Along it.** The core's centroid c̄ has the axial place s = (c̄ − P)·â; its travel
//!   toward the head is |s − s_head| in the slide's first frame less its least value in the
//!   slide, s_head the head body's axial place in the first frame.

use std::f64::consts::TAU;
use std::path::Path;

use glam::DVec3;

use crate::centreline::Centreline;
use crate::error::ReportError;
use crate::forces::ThigmoForces;
use crate::metrics_table::{MetricsCsv, number};

/// The phase whose frames are measured.
const SLIDE_PHASE: &str = "slide";

/// The measures of one run's slide around a cylinder.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotAroundCylinder {
    /// Turns w of the closed core about the axis in the slide's first frame with a core.
    pub turns_at_slide_start: f64,
    /// The least |w| over the slide's frames with a core: ≥ 1 when the knot stayed around
    /// the cylinder all through the slide.
    pub least_turns: f64,
    /// Share of the slide's frames that show a knotted core.
    pub shown: f64,
    /// The core centroid's travel along the axis toward the head in the slide (cm).
    pub axial_travel_cm: f64,
    /// The slide's thigmotaxic force: mean |f| over its frames and every DOF (dyn·cm).
    pub slide_force: f64,
}

impl KnotAroundCylinder {
    /// Reads the run in `dir` against the cylinder whose axis passes through `point` along
    /// `axis` (cm; any length but zero), or says why it has no such measures (no file, no
    /// slide frame with a knotted core).
    pub fn read(dir: &Path, point: DVec3, axis: DVec3) -> Result<Self, ReportError> {
        let csv = MetricsCsv::read(dir)?;
        let (phase, first, last) =
            (csv.column("phase")?, csv.column("knot_first_body")?, csv.column("knot_last_body")?);
        let centreline = Centreline::read(&dir.join("centreline.csv"))?;
        let axis = axis.try_normalize().ok_or_else(|| csv.unusable("a cylinder axis of zero"))?;
        let centre = |frame: usize, body: usize| {
            DVec3::from(centreline.points[frame * centreline.bodies + body])
        };
        let axial = |x: DVec3| (x - point).dot(axis);
        let head = axial(centre(0, 0));
        let slide: Vec<usize> = (0..csv.rows.len().min(centreline.times.len()))
            .filter(|&f| csv.rows[f][phase] == SLIDE_PHASE)
            .collect();
        let mut turns = Vec::new();
        let mut distance = Vec::new();
        for &f in &slide {
            let (a, b) = (number(&csv.rows[f], first), number(&csv.rows[f], last));
            if !(a.is_finite() && b.is_finite() && b < centreline.bodies as f64 && a <= b) {
                continue;
            }
            let core: Vec<DVec3> = (a as usize..=b as usize).map(|k| centre(f, k)).collect();
            turns.push(turns_about_axis(&core, point, axis));
            let centroid = core.iter().sum::<DVec3>() / core.len() as f64;
            distance.push((axial(centroid) - head).abs());
        }
        let (Some(&start), Some(&first_distance)) = (turns.first(), distance.first()) else {
            return Err(csv.unusable("no slide frame shows a knotted core"));
        };
        let forces = ThigmoForces::read(&dir.join("forces.csv"))?;
        Ok(Self {
            turns_at_slide_start: start,
            least_turns: turns.iter().fold(f64::INFINITY, |m, w| m.min(w.abs())),
            shown: turns.len() as f64 / slide.len() as f64,
            axial_travel_cm: first_distance - distance.iter().fold(f64::INFINITY, |m, &d| m.min(d)),
            slide_force: forces.mean_abs(&slide).unwrap_or(0.0),
        })
    }
}

/// Turns of the polygon `points`, closed by the chord from its last point to its first,
/// about the line through `point` along `axis` (any length; NaN for a zero one): (1/2π) Σ Δφ
/// over its edges, each Δφ the edge's turn about the line in (−π, π] (module docs). An integer
/// when no edge passes within rounding of the line (the knotted core lies outside the
/// cylinder, so its polygon cannot).
pub fn turns_about_axis(points: &[DVec3], point: DVec3, axis: DVec3) -> f64 {
    let Some(axis) = axis.try_normalize() else { return f64::NAN };
    let (u, v) = axis.any_orthonormal_pair();
    let angle = |x: DVec3| {
        let r = (x - point).reject_from_normalized(axis);
        r.dot(v).atan2(r.dot(u))
    };
    let angles: Vec<f64> = points.iter().map(|&x| angle(x)).collect();
    let closed = angles.iter().zip(angles.iter().cycle().skip(1));
    let total: f64 = closed.map(|(a, b)| (b - a + TAU / 2.0).rem_euclid(TAU) - TAU / 2.0).sum();
    total / TAU
}

#[cfg(test)]
mod tests {
    use super::*;

    fn helix(turns: f64, radius: f64, centre: DVec3, samples: usize) -> Vec<DVec3> {
        (0..samples)
            .map(|k| {
                let phi = TAU * turns * k as f64 / (samples - 1) as f64;
                centre + DVec3::new(0.3 * phi, radius * phi.cos(), radius * phi.sin())
            })
            .collect()
    }

    #[test]
    fn a_coil_about_the_axis_counts_its_turns_and_a_loop_beside_it_none() {
        let (origin, x) = (DVec3::ZERO, DVec3::X);
        for turns in [1.0, 2.0, 3.0] {
            let coil = helix(turns, 2.0, origin, 200);
            assert!((turns_about_axis(&coil, origin, x) - turns).abs() < 1e-9, "{turns}");
            let reversed: Vec<DVec3> = coil.iter().rev().copied().collect();
            assert!((turns_about_axis(&reversed, origin, x) + turns).abs() < 1e-9);
            // The axis may point either way, have any length and pass through any of its
            // points.
            let shifted = turns_about_axis(&coil, DVec3::new(7.0, 0.0, 0.0), -3.0 * x);
            assert!((shifted + turns).abs() < 1e-9);
        }
        // A loop of radius 2 about a line 5 cm away does not go round it.
        let beside = helix(1.0, 2.0, DVec3::new(0.0, 5.0, 0.0), 200);
        assert!(turns_about_axis(&beside, origin, x).abs() < 1e-9);
        // Half a turn (over the top, z ≥ 0) closed by its chord along z = 0: a whole turn
        // about an axis just above the chord, none about one just below it.
        let half = helix(0.5, 2.0, origin, 200);
        let above = turns_about_axis(&half, DVec3::new(0.0, 0.0, 0.1), x);
        assert!((above.abs() - 1.0).abs() < 1e-9, "{above}");
        assert!(turns_about_axis(&half, DVec3::new(0.0, 0.0, -0.1), x).abs() < 1e-9);
        assert!(turns_about_axis(&half, origin, DVec3::ZERO).is_nan());
    }
}
