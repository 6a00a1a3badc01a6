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

use std::cmp::Ordering;

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

/// Reduces `candidates` in place to one per cluster (the one with the smallest gap),
/// sorted by (u_a, u_b), and returns how many were merged away. Sorting is unstable but
/// over a total order, so the result does not depend on the input order; nothing
/// allocates.
pub(crate) fn keep_deepest_per_cluster(candidates: &mut Vec<Candidate>, radius: f64) -> usize {
    candidates.sort_unstable_by(deepest_first);
    let mut kept = 0;
    for index in 0..candidates.len() {
        let candidate = candidates[index];
        let duplicate = candidates[..kept].iter().any(|k| {
            (k.u_a - candidate.u_a).abs() <= radius && (k.u_b - candidate.u_b).abs() <= radius
        });
        if !duplicate {
            candidates[kept] = candidate;
            kept += 1;
        }
    }
    let merged = candidates.len() - kept;
    candidates.truncate(kept);
    candidates.sort_unstable_by(anterior_first);
    merged
}

#[cfg(test)]
mod tests {
    use super::*;

    fn candidate(u_a: f64, u_b: f64, gap: f64) -> Candidate {
        Candidate { u_a, u_b, gap, status: NewtonStatus::Converged }
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
}
