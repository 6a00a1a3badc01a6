//! The thigmotaxic force field over a run and its statistics (thesis §6.3, Figure 6.2).
//!
//! Every recorded frame keeps `f_thigmo = C_thigmoᵀλ_thigmo / h` per DOF with the knot's
//! contact span; [`ForceFieldLog::stats`] summarises one phase the way the thesis describes the
//! field: zero tail-ward of the knot, growing as the knot nears the head, smooth along the body
//! and rough in time.

use hagfish_control::KnotSpan;

use crate::forces::DofLabel;

/// One frame of the force field.
#[derive(Clone, Debug)]
struct FieldFrame {
    time: f64,
    phase: String,
    span: Option<KnotSpan>,
    /// `f_thigmo` per DOF (dyn·cm).
    values: Vec<f64>,
}

/// The thigmotaxic force of every recorded frame, with where each DOF sits along the body.
#[derive(Clone, Debug, Default)]
pub struct ForceFieldLog {
    labels: Vec<DofLabel>,
    /// Arc length of each DOF's joint from the head body's centre, on the straight body (cm),
    /// the convention of [`KnotSpan`].
    dof_arc_cm: Vec<f64>,
    frames: Vec<FieldFrame>,
}

/// Statistics of the force field over one phase.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ForceFieldStats {
    /// Frames of the phase.
    pub frames: usize,
    /// Largest |f_thigmo| of the whole run (dyn·cm).
    pub run_max_dyn_cm: f64,
    /// (DOF, frame) samples whose joint lies tail-ward of the knot's last contact point.
    pub tailward_samples: usize,
    /// Fraction of those with |f| < 1 % of the run's maximum.
    pub tailward_zero_fraction: f64,
    /// Mean |f| over all DOFs and frames of the phase (dyn·cm).
    pub mean_dyn_cm: f64,
    /// Mean |f| over all DOFs in the first quarter of the phase (by time, dyn·cm).
    pub first_quarter_mean_dyn_cm: f64,
    /// Mean |f| over all DOFs in the last quarter of the phase (dyn·cm).
    pub last_quarter_mean_dyn_cm: f64,
    /// Mean |f_j+1 − f_j| between neighbouring joints (same axis) over the phase, divided by
    /// the phase's mean |f|: small = smooth along the body.
    pub spatial_roughness: f64,
    /// Mean |f(t_k+1) − f(t_k)| between consecutive frames (same DOF), divided by the phase's
    /// mean |f|: large = rough in time.
    pub temporal_roughness: f64,
}

impl ForceFieldLog {
    /// An empty log for DOFs with these labels and joint positions (cm from the head body's
    /// centre).
    pub fn new(labels: Vec<DofLabel>, dof_arc_cm: Vec<f64>) -> Self {
        Self { labels, dof_arc_cm, frames: Vec::new() }
    }

    /// Appends one frame's `f_thigmo` (indexed like `q`).
    pub fn push(&mut self, time: f64, phase: &str, span: Option<KnotSpan>, thigmo: &[f64]) {
        self.frames.push(FieldFrame {
            time,
            phase: phase.to_string(),
            span,
            values: thigmo.to_vec(),
        });
    }

    /// Names of the phases in the log, in order of first appearance.
    pub fn phases(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        for frame in &self.frames {
            if !names.contains(&frame.phase.as_str()) {
                names.push(&frame.phase);
            }
        }
        names
    }

    /// Statistics of the frames of `phase`, or `None` if it has fewer than 4 frames.
    pub fn stats(&self, phase: &str) -> Option<ForceFieldStats> {
        let frames: Vec<&FieldFrame> = self.frames.iter().filter(|f| f.phase == phase).collect();
        if frames.len() < 4 {
            return None;
        }
        let run_max =
            self.frames.iter().flat_map(|f| f.values.iter()).fold(0.0_f64, |m, v| m.max(v.abs()));
        let (mut tailward, mut zero) = (0_usize, 0_usize);
        for frame in &frames {
            let Some(span) = frame.span else { continue };
            for (value, arc) in frame.values.iter().zip(&self.dof_arc_cm) {
                if *arc > span.end_cm {
                    tailward += 1;
                    zero += usize::from(value.abs() < 0.01 * run_max);
                }
            }
        }
        let (t0, t1) = (frames[0].time, frames[frames.len() - 1].time);
        let quarter = 0.25 * (t1 - t0);
        let mean_abs = |selected: &mut dyn Iterator<Item = &&FieldFrame>| {
            let (sum, count) = selected
                .flat_map(|f| f.values.iter())
                .fold((0.0, 0_usize), |(s, n), v| (s + v.abs(), n + 1));
            if count == 0 { 0.0 } else { sum / count as f64 }
        };
        let phase_mean = mean_abs(&mut frames.iter());
        let normalise = |x: f64| if phase_mean > 0.0 { x / phase_mean } else { 0.0 };
        Some(ForceFieldStats {
            frames: frames.len(),
            run_max_dyn_cm: run_max,
            mean_dyn_cm: phase_mean,
            tailward_samples: tailward,
            tailward_zero_fraction: if tailward == 0 { 1.0 } else { zero as f64 / tailward as f64 },
            first_quarter_mean_dyn_cm: mean_abs(
                &mut frames.iter().filter(|f| f.time <= t0 + quarter),
            ),
            last_quarter_mean_dyn_cm: mean_abs(
                &mut frames.iter().filter(|f| f.time >= t1 - quarter),
            ),
            spatial_roughness: normalise(self.spatial_variation(&frames)),
            temporal_roughness: normalise(temporal_variation(&frames)),
        })
    }

    /// Mean |f_j+1 − f_j| over neighbouring joints with the same axis, over `frames`.
    fn spatial_variation(&self, frames: &[&FieldFrame]) -> f64 {
        let pairs: Vec<(usize, usize)> = (0..self.labels.len())
            .filter_map(|i| {
                let next = self.labels.iter().position(|l| {
                    l.joint == self.labels[i].joint + 1 && l.axis == self.labels[i].axis
                })?;
                Some((i, next))
            })
            .collect();
        let (sum, count) = frames
            .iter()
            .flat_map(|f| pairs.iter().map(|&(i, j)| (f.values[j] - f.values[i]).abs()))
            .fold((0.0, 0_usize), |(s, n), d| (s + d, n + 1));
        if count == 0 { 0.0 } else { sum / count as f64 }
    }
}

/// Mean |f(t_k+1) − f(t_k)| over DOFs and consecutive frames.
fn temporal_variation(frames: &[&FieldFrame]) -> f64 {
    let (sum, count) = frames
        .windows(2)
        .flat_map(|w| w[0].values.iter().zip(&w[1].values).map(|(a, b)| (b - a).abs()))
        .fold((0.0, 0_usize), |(s, n), d| (s + d, n + 1));
    if count == 0 { 0.0 } else { sum / count as f64 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(joints: usize) -> Vec<DofLabel> {
        (0..joints).map(|joint| DofLabel { joint, axis: 'X' }).collect()
    }

    fn span(end_cm: f64) -> Option<KnotSpan> {
        Some(KnotSpan {
            start_cm: 0.0,
            end_cm,
            first_contact_cm: 0.0,
            last_contact_cm: 0.0,
            diameter_cm: 1.0,
        })
    }

    #[test]
    fn tailward_samples_are_those_past_the_knot_end() {
        let mut log = ForceFieldLog::new(labels(4), vec![0.0, 1.0, 2.0, 3.0]);
        for k in 0..4 {
            // Knot ends at 1.5 cm: DOFs 2 and 3 lie tail-ward; DOF 3 carries 5 % of the max.
            log.push(k as f64, "slide", span(1.5), &[100.0, 50.0, 0.0, 5.0]);
        }
        let stats = log.stats("slide").expect("4 frames");
        assert_eq!(stats.tailward_samples, 8);
        assert_eq!(stats.tailward_zero_fraction, 0.5);
        assert_eq!(stats.run_max_dyn_cm, 100.0);
    }

    #[test]
    fn quarters_and_roughness() {
        let mut log = ForceFieldLog::new(labels(2), vec![0.0, 1.0]);
        for k in 0..8 {
            let v = k as f64;
            log.push(v, "slide", None, &[v, v]);
        }
        let stats = log.stats("slide").expect("8 frames");
        // First quarter: t ≤ 1.75 → frames 0, 1; last: t ≥ 5.25 → frames 6, 7.
        assert_eq!(stats.first_quarter_mean_dyn_cm, 0.5);
        assert_eq!(stats.last_quarter_mean_dyn_cm, 6.5);
        assert_eq!(stats.spatial_roughness, 0.0);
        // |Δt f| = 1 everywhere; mean |f| = 3.5.
        assert!((stats.temporal_roughness - 1.0 / 3.5).abs() < 1e-15);
        assert_eq!(log.phases(), vec!["slide"]);
        assert!(log.stats("tighten").is_none());
    }
}
