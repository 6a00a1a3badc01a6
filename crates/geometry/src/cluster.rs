//! Merging the duplicate records of one physical crossing.
//!
//! One crossing is seen by several neighbouring body pairs and segment pairs, and a
//! closest point clamped to a segment end is usually the same point as the neighbouring
//! segment's result. Duplicate rows would make the contact matrix rank-deficient,
//! so records are clustered by parameter proximity and only the
//! deepest one per cluster is kept: greedy non-maximum suppression in order of increasing
//! gap. Records within the cluster radius of an already kept record, in both u_a and u_b,
//! are dropped. Along a line contact (two strands lying side by side) this keeps one
//! record every ~radius, which is what the solver needs there.
//!
//! The suppression runs while the records arrive ([`DeepestPerCluster`]), so that the detector
//! can skip searches whose record it would drop: fed segment pairs in order of increasing
//! lower bound on their gap, every record shallower than the next pair's bound is already
//! known, so its fate is final; and a pair whose whole parameter box lies within the cluster
//! radius of a kept record shallower than its own bound can only give a record that this
//! kept one drops. A dropped record suppresses nothing, so skipping it leaves the kept
//! records exactly as they are with every record present.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::contact::SelfContact;
use crate::narrow_phase::NewtonStatus;

/// A contact before merging: where it is, how deep, and how to rebuild its full record.
/// Kept small so that sorting and merging move little data; only the survivors become
/// [`crate::SelfContact`]s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Candidate {
    /// Spline parameter of the anterior point.
    pub(crate) u_a: f64,
    /// Spline parameter of the posterior point.
    pub(crate) u_b: f64,
    /// Tube gap (cm).
    pub(crate) gap: f64,
    /// Outcome of the closest-point search.
    pub(crate) status: NewtonStatus,
}

/// Total order used to pick the representative of a cluster: smallest gap first, then
/// converged before failed searches, then by parameters (for determinism on ties).
fn deepest_first(x: &Candidate, y: &Candidate) -> Ordering {
    x.gap
        .total_cmp(&y.gap)
        .then(x.status.cmp(&y.status))
        .then(x.u_a.total_cmp(&y.u_a))
        .then(x.u_b.total_cmp(&y.u_b))
}

/// Head-to-tail order of the output: by u_a, then u_b.
fn anterior_first(x: &Candidate, y: &Candidate) -> Ordering {
    x.u_a.total_cmp(&y.u_a).then(x.u_b.total_cmp(&y.u_b))
}

/// A candidate ordered so that the deepest is the greatest (the top of a max-heap).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Deepest(Candidate);

impl Eq for Deepest {}

impl Ord for Deepest {
    fn cmp(&self, other: &Self) -> Ordering {
        deepest_first(&other.0, &self.0)
    }
}

impl PartialOrd for Deepest {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Greedy non-maximum suppression of records as they arrive (module docs): the records not
/// yet judged (those pushed since the last [`settle_below`](Self::settle_below), and the
/// others deepest on top) and those kept so far. The result does not depend on the order
/// records are pushed in (a total order decides), and nothing allocates after
/// [`reserve`](Self::reserve).
#[derive(Debug, Clone, Default)]
pub(crate) struct DeepestPerCluster {
    radius: f64,
    arrived: Vec<Candidate>,
    pending: BinaryHeap<Deepest>,
    kept: Vec<Candidate>,
    merged: usize,
}

impl DeepestPerCluster {
    /// Room for `records` records.
    pub(crate) fn reserve(&mut self, records: usize) {
        self.arrived.reserve(records);
        self.pending.reserve(records);
        self.kept.reserve(records);
    }

    /// Starts afresh, with records closer than `radius` in both parameters one cluster.
    pub(crate) fn clear(&mut self, radius: f64) {
        self.radius = radius;
        self.arrived.clear();
        self.pending.clear();
        self.kept.clear();
        self.merged = 0;
    }

    /// Adds a record, judged by a later [`settle_below`](Self::settle_below) or
    /// [`finish`](Self::finish).
    pub(crate) fn push(&mut self, candidate: Candidate) {
        self.arrived.push(candidate);
    }

    /// Judges every pending record with a gap below `gap`, deepest first. Final when no
    /// record still to come has a gap below `gap`.
    pub(crate) fn settle_below(&mut self, gap: f64) {
        self.pending.extend(self.arrived.drain(..).map(Deepest));
        while let Some(&Deepest(candidate)) = self.pending.peek() {
            if candidate.gap >= gap {
                break;
            }
            self.pending.pop();
            self.judge(candidate);
        }
    }

    /// Keeps `candidate` unless a kept record lies within the radius in both parameters.
    fn judge(&mut self, candidate: Candidate) {
        let radius = self.radius;
        let duplicate = self.kept.iter().any(|k| {
            (k.u_a - candidate.u_a).abs() <= radius && (k.u_b - candidate.u_b).abs() <= radius
        });
        if duplicate {
            self.merged += 1;
        } else {
            self.kept.push(candidate);
        }
    }

    /// The records kept so far, in the order they were kept.
    pub(crate) fn kept(&self) -> &[Candidate] {
        &self.kept
    }

    /// Judges the remaining records and returns the kept ones sorted by (u_a, u_b), with how
    /// many records were merged away.
    pub(crate) fn finish(&mut self) -> (&[Candidate], usize) {
        // All at once: one sort instead of a pop per record (the heap's buffer is reused).
        let mut records = std::mem::take(&mut self.pending).into_vec();
        records.extend(self.arrived.drain(..).map(Deepest));
        records.sort_unstable_by(|x, y| deepest_first(&x.0, &y.0));
        for &Deepest(candidate) in &records {
            self.judge(candidate);
        }
        records.clear();
        self.pending = BinaryHeap::from(records);
        self.kept.sort_unstable_by(anterior_first);
        (&self.kept, self.merged)
    }
}

/// The records a coarser cluster radius keeps of a detector's output: greedy non-maximum
/// suppression (deepest first, as the detector's own) at `radius` over records already merged
/// at a finer one. Along a line contact the detector keeps one record per cluster radius, so
/// the finer the radius the more records stand for the same stretch; a law summed over the
/// records, such as the skin's springs, is only the same at every resolution on the records one
/// radius keeps. Nothing allocates after [`reserve`](Self::reserve).
#[derive(Debug, Clone, Default)]
pub struct CoarserClusters {
    clusters: DeepestPerCluster,
    kept: Vec<bool>,
}

impl CoarserClusters {
    /// Room for `records` records.
    pub fn reserve(&mut self, records: usize) {
        self.clusters.reserve(records);
        self.kept.reserve(records);
    }

    /// One flag per record of `contacts` (sorted head to tail by (u_a, u_b), as
    /// [`crate::ContactDetector::detect`] writes them): whether suppression at `radius`
    /// keeps it.
    pub fn keep(&mut self, contacts: &[SelfContact], radius: f64) -> &[bool] {
        self.clusters.clear(radius);
        for contact in contacts {
            let (u_a, u_b, gap, status) = (contact.u_a, contact.u_b, contact.gap, contact.status);
            self.clusters.push(Candidate { u_a, u_b, gap, status });
        }
        let (kept, _) = self.clusters.finish();
        // Both lists are in head-to-tail order and the kept records are copies of some of
        // `contacts`: one walk marks them.
        let mut next = kept.iter().peekable();
        self.kept.clear();
        for contact in contacts {
            let is_kept = next.next_if(|k| k.u_a == contact.u_a && k.u_b == contact.u_b).is_some();
            self.kept.push(is_kept);
        }
        &self.kept
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn candidate(u_a: f64, u_b: f64, gap: f64) -> Candidate {
        Candidate { u_a, u_b, gap, status: NewtonStatus::Converged }
    }

    /// The kept records of `candidates` pushed all at once, and how many were merged.
    fn keep_deepest_per_cluster(candidates: &mut Vec<Candidate>, radius: f64) -> usize {
        let mut clusters = DeepestPerCluster::default();
        clusters.clear(radius);
        for &candidate in candidates.iter() {
            clusters.push(candidate);
        }
        let (kept, merged) = clusters.finish();
        *candidates = kept.to_vec();
        merged
    }

    #[test]
    fn keeps_the_deepest_candidate_per_cluster_sorted_head_to_tail() {
        let mut candidates = vec![
            candidate(30.0, 60.0, -0.10),
            candidate(10.2, 40.1, -0.05),
            candidate(10.9, 41.0, -0.20),
            candidate(30.5, 61.2, -0.30),
            candidate(11.5, 42.0, -0.01),
            candidate(10.0, 45.0, -0.02),
        ];
        let merged = keep_deepest_per_cluster(&mut candidates, 1.5);
        let kept: Vec<_> = candidates.iter().map(|c| (c.u_a, c.u_b)).collect();
        assert_eq!(kept, vec![(10.0, 45.0), (10.9, 41.0), (30.5, 61.2)]);
        assert_eq!(merged, 3);
    }

    #[test]
    fn converged_wins_a_tie_and_result_does_not_depend_on_input_order() {
        let mut tie = vec![
            Candidate { status: NewtonStatus::Stalled, ..candidate(5.0, 20.0, -0.1) },
            candidate(5.0, 20.0, -0.1),
        ];
        keep_deepest_per_cluster(&mut tie, 1.5);
        assert_eq!(tie, vec![candidate(5.0, 20.0, -0.1)]);
        let candidates: Vec<_> = (0..12)
            .map(|k| {
                candidate(f64::from(k) * 0.7, 20.0 + f64::from(k % 5), -0.01 * f64::from(k % 4))
            })
            .collect();
        let mut reference = candidates.clone();
        keep_deepest_per_cluster(&mut reference, 1.5);
        for rotation in 1..candidates.len() {
            let mut rotated = candidates.clone();
            rotated.rotate_left(rotation);
            rotated.reverse();
            keep_deepest_per_cluster(&mut rotated, 1.5);
            assert_eq!(rotated, reference);
        }
    }

    #[test]
    fn records_judged_as_they_arrive_are_those_judged_at_the_end() {
        // Records arrive in batches whose gaps are at least the batch's bound (as a segment
        // pair's records are at least its gap bound); each batch first settles below its bound.
        let records: Vec<Candidate> = (0..40)
            .map(|k| {
                let x = f64::from(k);
                candidate((0.37 * x).sin() * 6.0 + 10.0, (0.71 * x).cos() * 6.0 + 30.0, 0.01 * x)
            })
            .collect();
        let mut all_at_once = records.clone();
        let merged_at_once = keep_deepest_per_cluster(&mut all_at_once, 1.5);
        let mut clusters = DeepestPerCluster::default();
        clusters.clear(1.5);
        for batch in records.chunks(7) {
            let bound = batch.iter().map(|c| c.gap).fold(f64::INFINITY, f64::min);
            clusters.settle_below(bound);
            for &c in batch.iter().rev() {
                clusters.push(c);
            }
        }
        let (kept, merged) = clusters.finish();
        assert_eq!(kept, all_at_once.as_slice());
        assert_eq!(merged, merged_at_once);
        assert!(merged > 0 && kept.len() > 1, "the case merges some and keeps several");
    }

    /// A hairpin of 60 unit bodies, radius 0.6: two straight legs 1.1 apart (skins pressed
    /// 0.1 together) over their length, bent round at body 30 — one long line contact.
    fn hairpin() -> (crate::Centreline, Vec<f64>) {
        use glam::DVec3;
        let centres: Vec<DVec3> = (0..60)
            .map(|i| {
                let s = f64::from(i);
                if i <= 30 {
                    DVec3::new(s, 0.0, 0.0)
                } else {
                    // Back along y = 1.1, converging by 1e-3 per body so the gaps differ.
                    DVec3::new(60.0 - s, 1.1 - 1e-3 * (s - 30.0), 0.0)
                }
            })
            .collect();
        let line = crate::Centreline::new(&centres, &[0.6; 60]).expect("a centreline");
        (line, vec![1.0; 60])
    }

    fn detect(line: &crate::Centreline, lengths: &[f64], cluster_radius: f64) -> Vec<SelfContact> {
        let options =
            crate::DetectorOptions { cluster_radius, ..crate::DetectorOptions::default() };
        let mut detector = crate::ContactDetector::new(options).expect("a detector");
        let mut contacts = Vec::new();
        detector.detect(line, lengths, &mut contacts).expect("detection");
        contacts
    }

    #[test]
    fn coarser_clusters_thin_a_line_contact_to_the_coarse_radius_and_keep_the_deepest() {
        let (line, lengths) = hairpin();
        let fine = detect(&line, &lengths, 1.5);
        let coarse = detect(&line, &lengths, 4.5);
        assert!(
            fine.len() > 2 * coarse.len() && coarse.len() > 3,
            "{} {}",
            fine.len(),
            coarse.len()
        );
        let mut coarser = CoarserClusters::default();
        // At the radius they were merged at, every record stays.
        assert!(coarser.keep(&fine, 1.5).iter().all(|&k| k));
        // At the coarse radius, about as many as the detector keeps there, the deepest among them.
        let kept = coarser.keep(&fine, 4.5).to_vec();
        let count = kept.iter().filter(|&&k| k).count();
        assert!(count.abs_diff(coarse.len()) <= 1, "{count} kept, the detector {}", coarse.len());
        let deepest = (0..fine.len()).min_by(|&i, &j| fine[i].gap.total_cmp(&fine[j].gap));
        assert!(kept[deepest.expect("records")]);
        // Kept records are more than the radius apart in one parameter or the other.
        let kept_records: Vec<_> = fine.iter().zip(&kept).filter(|(_, k)| **k).collect();
        for (i, (x, _)) in kept_records.iter().enumerate() {
            for (y, _) in &kept_records[i + 1..] {
                assert!((x.u_a - y.u_a).abs() > 4.5 || (x.u_b - y.u_b).abs() > 4.5);
            }
        }
        // A radius larger than the body keeps the deepest record alone.
        let one = coarser.keep(&fine, 100.0);
        assert_eq!(one.iter().filter(|&&k| k).count(), 1);
        assert!(one[deepest.expect("records")]);
    }
}
