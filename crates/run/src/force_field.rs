//! The thigmotaxic force field over a run and its statistics (thesis §6.3, Figure 6.2).
//!
//! Every recorded frame's `f_thigmo = C_thigmoᵀλ_thigmo / h` per DOF, with the knot's contact
//! span, is folded into per-phase sums as it arrives; [`ForceFieldLog::stats`] summarises one
//! phase the way the thesis describes the field: zero tail-ward of the knot, growing as the
//! knot nears the head, smooth along the body and rough in time. The log keeps O(frames +
//! phases × DOFs) numbers, not the field itself: a 10 000-body run records 15 000 DOFs a frame
//! (120 kB), which kept for every frame would grow with bodies × frames.

use std::collections::HashMap;

use hagfish_control::KnotSpan;

use hagfish_sim::DofLabel;

/// The sums of one recorded frame that the quarter means need (the phase's first and last
/// times are known only at its end).
#[derive(Clone, Copy, Debug)]
struct FrameSum {
    time: f64,
    /// Σ|f| over the DOFs (dyn·cm), and their number.
    abs_sum: (f64, usize),
}

/// Running sums of one phase (frames with the same phase name, in order).
#[derive(Clone, Debug, Default)]
struct PhaseSums {
    name: String,
    frames: Vec<FrameSum>,
    /// Σ|f| over DOFs and frames, in the order they came, and its term count.
    abs_sum: (f64, usize),
    /// Σ|f_j+1 − f_j| over neighbouring joints (same axis) and frames, and its term count.
    spatial: (f64, usize),
    /// Σ|f(t_k+1) − f(t_k)| over DOFs and consecutive frames of the phase, and its count.
    temporal: (f64, usize),
    /// The phase's previous frame, for the temporal sum.
    previous: Vec<f64>,
    /// (DOF, frame) samples tail-ward of the knot's last contact point.
    tailward: usize,
    /// Of those, the ones already below 1 % of the run's maximum when they came (below it at
    /// the end too: the maximum only grows).
    tailward_zero: usize,
    /// Tail-ward |f| at or above 1 % of the maximum so far: decided against the run's final
    /// maximum (exact zeros are counted apart, as `tailward_exact_zeros`).
    tailward_pending: Vec<f64>,
    /// Tail-ward samples of exactly 0 that came while the maximum was 0: zero once any
    /// force is non-zero.
    tailward_exact_zeros: usize,
}

/// The thigmotaxic force of every recorded frame, folded into per-phase sums, with where
/// each DOF sits along the body.
#[derive(Clone, Debug, Default)]
pub struct ForceFieldLog {
    /// Arc length of each DOF's joint from the head body's centre, on the straight body (cm),
    /// the convention of [`KnotSpan`].
    dof_arc_cm: Vec<f64>,
    /// DOF pairs (i, j): j is the first DOF of the next joint on the same axis as i.
    neighbours: Vec<(usize, usize)>,
    /// Largest |f_thigmo| so far (dyn·cm).
    run_max: f64,
    /// The run maximum when the pending samples were last sorted out.
    pruned_at_max: f64,
    /// In order of first appearance.
    phases: Vec<PhaseSums>,
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

/// The share of the run maximum below which a tail-ward force counts as zero.
const ZERO_SHARE: f64 = 0.01;

impl ForceFieldLog {
    /// An empty log for DOFs with these labels and joint positions (cm from the head body's
    /// centre).
    pub fn new(labels: Vec<DofLabel>, dof_arc_cm: Vec<f64>) -> Self {
        let mut first_of = HashMap::new();
        for (i, label) in labels.iter().enumerate() {
            first_of.entry((label.joint, label.axis)).or_insert(i);
        }
        let neighbours = labels
            .iter()
            .enumerate()
            .filter_map(|(i, l)| Some((i, *first_of.get(&(l.joint + 1, l.axis))?)))
            .collect();
        Self { dof_arc_cm, neighbours, ..Self::default() }
    }

    /// Folds one frame's `f_thigmo` (indexed like `q`) into its phase's sums.
    pub fn push(&mut self, time: f64, phase: &str, span: Option<KnotSpan>, thigmo: &[f64]) {
        self.run_max = thigmo.iter().fold(self.run_max, |m, v| m.max(v.abs()));
        let index = match self.phases.iter().position(|p| p.name == phase) {
            Some(index) => index,
            None => {
                self.phases.push(PhaseSums { name: phase.to_string(), ..PhaseSums::default() });
                self.phases.len() - 1
            }
        };
        let (run_max, neighbours, dof_arc_cm) = (self.run_max, &self.neighbours, &self.dof_arc_cm);
        let sums = &mut self.phases[index];
        let frame_sum = thigmo.iter().fold(0.0, |s, v| s + v.abs());
        sums.frames.push(FrameSum { time, abs_sum: (frame_sum, thigmo.len()) });
        sums.abs_sum.0 = thigmo.iter().fold(sums.abs_sum.0, |s, v| s + v.abs());
        sums.abs_sum.1 += thigmo.len();
        for &(i, j) in neighbours {
            sums.spatial.0 += (thigmo[j] - thigmo[i]).abs();
        }
        sums.spatial.1 += neighbours.len();
        if sums.frames.len() > 1 {
            for (a, b) in sums.previous.iter().zip(thigmo) {
                sums.temporal.0 += (b - a).abs();
            }
            sums.temporal.1 += sums.previous.len().min(thigmo.len());
        }
        sums.previous.clear();
        sums.previous.extend_from_slice(thigmo);
        if let Some(span) = span {
            for (value, arc) in thigmo.iter().zip(dof_arc_cm) {
                if *arc > span.end_cm {
                    sums.tailward += 1;
                    let size = value.abs();
                    if size < ZERO_SHARE * run_max {
                        sums.tailward_zero += 1;
                    } else if size == 0.0 {
                        sums.tailward_exact_zeros += 1;
                    } else {
                        sums.tailward_pending.push(size);
                    }
                }
            }
        }
        if self.run_max > 2.0 * self.pruned_at_max {
            self.sort_out_pending();
        }
    }

    /// Counts the pending samples now below 1 % of the run maximum as zero and drops them
    /// (and the exact zeros once the maximum is positive): done each time the maximum has
    /// doubled, so that only samples near the threshold stay.
    fn sort_out_pending(&mut self) {
        let threshold = ZERO_SHARE * self.run_max;
        for sums in &mut self.phases {
            let before = sums.tailward_pending.len();
            sums.tailward_pending.retain(|&size| size >= threshold);
            sums.tailward_zero += before - sums.tailward_pending.len();
            if self.run_max > 0.0 {
                sums.tailward_zero += std::mem::take(&mut sums.tailward_exact_zeros);
            }
        }
        self.pruned_at_max = self.run_max;
    }

    /// Names of the phases in the log, in order of first appearance.
    pub fn phases(&self) -> Vec<&str> {
        self.phases.iter().map(|p| p.name.as_str()).collect()
    }

    /// Statistics of the frames of `phase`, or `None` if it has fewer than 4 frames.
    pub fn stats(&self, phase: &str) -> Option<ForceFieldStats> {
        let sums = self.phases.iter().find(|p| p.name == phase)?;
        let frames = &sums.frames;
        if frames.len() < 4 {
            return None;
        }
        let threshold = ZERO_SHARE * self.run_max;
        // Exact zeros still apart are those of a run whose forces are all 0: not below 1 % of
        // a maximum of 0 (the first non-zero force moves them to `tailward_zero`).
        let zero = sums.tailward_zero
            + sums.tailward_pending.iter().filter(|&&size| size < threshold).count();
        let mean = |(sum, count): (f64, usize)| if count == 0 { 0.0 } else { sum / count as f64 };
        let (t0, t1) = (frames[0].time, frames[frames.len() - 1].time);
        let quarter = 0.25 * (t1 - t0);
        let quarter_mean = |keep: &dyn Fn(f64) -> bool| {
            let kept = frames.iter().filter(|f| keep(f.time));
            mean(kept.fold((0.0, 0), |(s, n), f| (s + f.abs_sum.0, n + f.abs_sum.1)))
        };
        let phase_mean = mean(sums.abs_sum);
        let normalise = |x: f64| if phase_mean > 0.0 { x / phase_mean } else { 0.0 };
        Some(ForceFieldStats {
            frames: frames.len(),
            run_max_dyn_cm: self.run_max,
            mean_dyn_cm: phase_mean,
            tailward_samples: sums.tailward,
            tailward_zero_fraction: if sums.tailward == 0 {
                1.0
            } else {
                zero as f64 / sums.tailward as f64
            },
            first_quarter_mean_dyn_cm: quarter_mean(&|t| t <= t0 + quarter),
            last_quarter_mean_dyn_cm: quarter_mean(&|t| t >= t1 - quarter),
            spatial_roughness: normalise(mean(sums.spatial)),
            temporal_roughness: normalise(mean(sums.temporal)),
        })
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

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

    #[test]
    fn zeros_seen_while_every_force_is_zero_count_once_one_is_not() {
        let quiet = |log: &mut ForceFieldLog, from: usize| {
            for k in from..from + 4 {
                log.push(k as f64, "hold", span(0.5), &[0.0, 0.0, 0.0, 0.0]);
            }
        };
        let mut all_zero = ForceFieldLog::new(labels(4), vec![0.0, 1.0, 2.0, 3.0]);
        quiet(&mut all_zero, 0);
        let stats = all_zero.stats("hold").expect("4 frames");
        assert_eq!((stats.tailward_samples, stats.tailward_zero_fraction), (12, 0.0));
        let mut then_force = all_zero.clone();
        then_force.push(4.0, "slide", None, &[10.0, 0.0, 0.0, 0.0]);
        let stats = then_force.stats("hold").expect("4 frames");
        assert_eq!((stats.tailward_samples, stats.tailward_zero_fraction), (12, 1.0));
    }

    /// The statistics from the whole field kept in memory (the definition, computed the
    /// direct way): the reference for the folded sums.
    fn reference(
        labels: &[DofLabel],
        arcs: &[f64],
        frames: &[(f64, &str, Option<KnotSpan>, Vec<f64>)],
        phase: &str,
    ) -> Option<ForceFieldStats> {
        let all: Vec<&Vec<f64>> = frames.iter().map(|f| &f.3).collect();
        let mine: Vec<_> = frames.iter().filter(|f| f.1 == phase).collect();
        if mine.len() < 4 {
            return None;
        }
        let run_max = all.iter().flat_map(|v| v.iter()).fold(0.0_f64, |m, v| m.max(v.abs()));
        let (mut tailward, mut zero) = (0, 0);
        for f in &mine {
            let Some(span) = f.2 else { continue };
            for (v, arc) in f.3.iter().zip(arcs) {
                if *arc > span.end_cm {
                    tailward += 1;
                    zero += usize::from(v.abs() < 0.01 * run_max);
                }
            }
        }
        let mean_abs = |selected: &[&&(f64, &str, Option<KnotSpan>, Vec<f64>)]| {
            let values: Vec<f64> =
                selected.iter().flat_map(|f| f.3.iter().map(|v| v.abs())).collect();
            values.iter().sum::<f64>() / values.len().max(1) as f64
        };
        let (t0, t1) = (mine[0].0, mine[mine.len() - 1].0);
        let quarter = 0.25 * (t1 - t0);
        let all_mine: Vec<_> = mine.iter().collect();
        let first: Vec<_> = mine.iter().filter(|f| f.0 <= t0 + quarter).collect();
        let last: Vec<_> = mine.iter().filter(|f| f.0 >= t1 - quarter).collect();
        let phase_mean = mean_abs(&all_mine);
        let mut spatial = Vec::new();
        for f in &mine {
            for i in 0..labels.len() {
                let next = labels
                    .iter()
                    .position(|l| l.joint == labels[i].joint + 1 && l.axis == labels[i].axis);
                spatial.extend(next.map(|j| (f.3[j] - f.3[i]).abs()));
            }
        }
        let temporal: Vec<f64> = mine
            .windows(2)
            .flat_map(|w| w[0].3.iter().zip(&w[1].3).map(|(a, b)| (b - a).abs()))
            .collect();
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
        let normalise = |x: f64| if phase_mean > 0.0 { x / phase_mean } else { 0.0 };
        Some(ForceFieldStats {
            frames: mine.len(),
            run_max_dyn_cm: run_max,
            tailward_samples: tailward,
            tailward_zero_fraction: if tailward == 0 { 1.0 } else { zero as f64 / tailward as f64 },
            mean_dyn_cm: phase_mean,
            first_quarter_mean_dyn_cm: mean_abs(&first),
            last_quarter_mean_dyn_cm: mean_abs(&last),
            spatial_roughness: normalise(mean(&spatial)),
            temporal_roughness: normalise(mean(&temporal)),
        })
    }

    /// A frame's forces: mostly small or zero, with a rare large one, so that the run's
    /// maximum grows in steps and the 1 % threshold moves past values already seen.
    fn force() -> impl Strategy<Value = f64> {
        prop_oneof![
            3 => Just(0.0),
            4 => -1.0..1.0_f64,
            2 => -100.0..100.0_f64,
            1 => -1e4..1e4_f64,
        ]
    }

    proptest! {
        #[test]
        fn the_folded_sums_give_the_statistics_of_the_whole_field(
            frames in proptest::collection::vec(
                (0..3_usize, proptest::option::of(0.0..4.0_f64), proptest::collection::vec(force(), 6)),
                4..40,
            ),
        ) {
            // Three joints: X, then Y and Z, then X (6 DOFs with the extra Y, Z of joint 2).
            let labels: Vec<DofLabel> = [(0, 'X'), (1, 'Y'), (1, 'Z'), (2, 'X'), (2, 'Y'), (2, 'Z')]
                .map(|(joint, axis)| DofLabel { joint, axis })
                .to_vec();
            let arcs = vec![0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
            let names = ["tie", "slide", "hold"];
            let frames: Vec<(f64, &str, Option<KnotSpan>, Vec<f64>)> = frames
                .into_iter()
                .enumerate()
                .map(|(k, (phase, end, values))| (0.1 * k as f64, names[phase], end.and_then(span), values))
                .collect();
            let mut log = ForceFieldLog::new(labels.clone(), arcs.clone());
            for (time, phase, span, values) in &frames {
                log.push(*time, phase, *span, values);
            }
            for phase in names {
                let (folded, direct) = (log.stats(phase), reference(&labels, &arcs, &frames, phase));
                prop_assert_eq!(folded.is_some(), direct.is_some());
                let (Some(folded), Some(direct)) = (folded, direct) else { continue };
                prop_assert_eq!(folded.frames, direct.frames);
                prop_assert_eq!(folded.run_max_dyn_cm, direct.run_max_dyn_cm);
                prop_assert_eq!(folded.tailward_samples, direct.tailward_samples);
                prop_assert_eq!(folded.tailward_zero_fraction, direct.tailward_zero_fraction);
                // Sums in another order: equal to rounding.
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()));
                for (a, b) in [
                    (folded.mean_dyn_cm, direct.mean_dyn_cm),
                    (folded.first_quarter_mean_dyn_cm, direct.first_quarter_mean_dyn_cm),
                    (folded.last_quarter_mean_dyn_cm, direct.last_quarter_mean_dyn_cm),
                    (folded.spatial_roughness, direct.spatial_roughness),
                    (folded.temporal_roughness, direct.temporal_roughness),
                ] {
                    prop_assert!(close(a, b), "{folded:?} against {direct:?}");
                }
            }
        }
    }
}
