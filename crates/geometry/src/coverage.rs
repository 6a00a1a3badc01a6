//! Which segment pairs a kept contact covers (`cluster.rs`): a pair whose whole parameter box
//! lies within the cluster radius of a kept record, in both parameters, can only give records
//! that this kept one drops.
//!
//! Where pairs are queued one by one (`pruning.rs`: fine chains below the radius of blocks)
//! each crossing is seen by hundreds to thousands of queued pairs and kept by a few records,
//! so the covered pairs are marked once per kept record, over the rows of the sorted pair list
//! that its radius reaches, instead of every pair asking every kept record. Where they come in
//! blocks, the few pairs of opened blocks ask the kept records themselves ([`covers`]).

use std::ops::Range;

use crate::cluster::Candidate;

/// Whether `center` lies within `radius` of both ends of the interval [`low`, `high`]: the
/// test of one parameter, in the floating-point operations of [`Coverage::mark`].
pub(crate) fn reaches(center: f64, radius: f64, low: f64, high: f64) -> bool {
    center - radius <= low && high <= center + radius
}

/// Whether `record` lies within `radius` of the whole box [k_a, k_a + 1] × [k_b, k_b + 1] of
/// segment pair `(k_a, k_b)` in both parameters: the test that [`Coverage::mark`] applies to
/// every pair it reaches.
pub(crate) fn covers(record: &Candidate, radius: f64, (k_a, k_b): (usize, usize)) -> bool {
    let (a, b) = (k_a as f64, k_b as f64);
    reaches(record.u_a, radius, a, a + 1.0) && reaches(record.u_b, radius, b, b + 1.0)
}

/// The covered pairs of one sorted pair list: per pair, whether a kept record covers it.
#[derive(Debug, Clone, Default)]
pub(crate) struct Coverage {
    covered: Vec<bool>,
}

impl Coverage {
    /// Room for `pairs` pairs.
    pub(crate) fn reserve(&mut self, pairs: usize) {
        self.covered.reserve(pairs);
    }

    /// Starts on a list of `pairs` pairs with none covered.
    pub(crate) fn reset(&mut self, pairs: usize) {
        self.covered.clear();
        self.covered.resize(pairs, false);
    }

    /// Marks every pair of `pairs` (sorted by (k_a, k_b); the list of the last
    /// [`reset`](Self::reset)) whose box [k_a, k_a + 1] × [k_b, k_b + 1] lies within `radius`
    /// of `record` in both parameters.
    pub(crate) fn mark(&mut self, pairs: &[(usize, usize)], record: &Candidate, radius: f64) {
        // Every k_a the test can accept, and one more on each side for rounding; the rows in
        // that range follow each other in the list, so one bisection finds the first.
        let first = (record.u_a - radius - 1.0).floor().max(0.0) as usize;
        let last = (record.u_a + radius + 1.0).ceil().max(0.0) as usize;
        let mut start = pairs.partition_point(|p| p.0 < first);
        for k_a in first..last {
            let end = start + pairs[start..].partition_point(|p| p.0 == k_a);
            let low = k_a as f64;
            if reaches(record.u_a, radius, low, low + 1.0) {
                let range = Self::within(&pairs[start..end], record.u_b, radius);
                self.covered[start + range.start..start + range.end].fill(true);
            }
            start = end;
        }
    }

    /// The pairs of one row whose k_b interval lies within `radius` of `u_b`: the test is
    /// monotone in k_b (false, true, false along the row), so the range is found by bisection.
    fn within(row: &[(usize, usize)], u_b: f64, radius: f64) -> Range<usize> {
        let from = row.partition_point(|p| u_b - radius > p.1 as f64);
        let to = row.partition_point(|p| p.1 as f64 + 1.0 <= u_b + radius);
        from..to.max(from)
    }

    /// Whether pair `index` of the pair list is covered.
    pub(crate) fn is_covered(&self, index: usize) -> bool {
        self.covered[index]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::narrow_phase::NewtonStatus;

    fn record(u_a: f64, u_b: f64) -> Candidate {
        Candidate { u_a, u_b, gap: -0.1, status: NewtonStatus::Converged }
    }

    #[test]
    fn a_box_is_covered_only_when_a_kept_record_reaches_all_of_it() {
        let pairs = [(9, 40), (10, 38), (10, 40), (11, 40)];
        let mut coverage = Coverage::default();
        coverage.reset(pairs.len());
        assert!((0..pairs.len()).all(|i| !coverage.is_covered(i)), "nothing is kept yet");
        coverage.mark(&pairs, &record(10.4, 40.6), 1.5);
        assert!(coverage.is_covered(2), "[10, 11] × [40, 41]");
        assert!(coverage.is_covered(0), "u_a 9 is 1.4 away");
        assert!(!coverage.is_covered(3), "u_a 12 is 1.6 away");
        assert!(!coverage.is_covered(1), "u_b 38 is 2.6 away");
    }

    proptest::proptest! {
        /// Marking gives exactly the pairs that the test of every pair against every record
        /// accepts, also for records exactly one radius from a segment end.
        #[test]
        fn marks_are_those_of_the_test_on_every_pair(
            raw_pairs in proptest::collection::vec((0_usize..60, 0_usize..60), 0..300),
            records in proptest::collection::vec((0_u32..600, 0_u32..600), 1..8),
            radius_tenths in 0_u32..80,
        ) {
            let mut pairs: Vec<(usize, usize)> =
                raw_pairs.into_iter().filter(|&(a, b)| a < b).collect();
            pairs.sort_unstable();
            pairs.dedup();
            let radius = f64::from(radius_tenths) / 10.0;
            let records: Vec<Candidate> = records
                .iter()
                .map(|&(a, b)| record(f64::from(a) / 10.0, f64::from(b) / 10.0))
                .collect();
            let mut coverage = Coverage::default();
            coverage.reset(pairs.len());
            for r in &records {
                coverage.mark(&pairs, r, radius);
            }
            for (i, &pair) in pairs.iter().enumerate() {
                let expected = records.iter().any(|r| covers(r, radius, pair));
                proptest::prop_assert_eq!(coverage.is_covered(i), expected, "pair {:?}", pair);
            }
        }
    }
}
