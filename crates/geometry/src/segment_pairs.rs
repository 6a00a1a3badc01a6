//! The segment pairs around the broad phase's body pairs: body i touches segments i − 1 and
//! i (those that exist), so segment k_a is touched by the body pairs of bodies k_a and
//! k_a + 1.

/// Fills `out` with the segment pairs (k_a, k_b), k_b − k_a ≥ `min_offset` (≥ 1) and
/// k_b < `segment_count`, touching the body pairs `body_pairs` (sorted by (i, j), i < j,
/// unique), sorted and unique.
///
/// Each of the two body rows of k_a gives its partners' segments k_b ∈ {j − 1, j} in order
/// ([`TouchedSegments`]); merging the two rows gives the pairs of k_a sorted. One forward pass
/// over the body pairs, visiting only the segments some pair touches: time and memory linear
/// in the pairs (no table over all S² segment pairs, no search per segment).
pub(crate) fn collect_segment_pairs(
    body_pairs: &[(usize, usize)],
    segment_count: usize,
    min_offset: usize,
    out: &mut Vec<(usize, usize)>,
) {
    out.clear();
    let row_end = |from: usize, body: usize| {
        from + body_pairs[from..].iter().take_while(|p| p.0 == body).count()
    };
    let mut k_a = body_pairs.first().map_or(usize::MAX, |p| p.0.saturating_sub(1));
    let mut start = 0;
    while k_a < segment_count {
        while body_pairs[start].0 < k_a {
            start += 1;
        }
        let middle = row_end(start, k_a);
        let end = row_end(middle, k_a + 1);
        let mut first = TouchedSegments { partners: &body_pairs[start..middle], position: 0 };
        let mut second = TouchedSegments { partners: &body_pairs[middle..end], position: 0 };
        let mut last = None;
        loop {
            let next = match (first.peek(), second.peek()) {
                (Some(a), Some(b)) if a <= b => first.advance(a),
                (_, Some(b)) => second.advance(b),
                (Some(a), None) => first.advance(a),
                (None, None) => break,
            };
            if next >= segment_count {
                break;
            }
            if k_a + min_offset <= next && last != Some(next) {
                out.push((k_a, next));
                last = Some(next);
            }
        }
        // The next segment that a body row touches: k_a + 1, or the one before the next row.
        k_a = match body_pairs.get(end) {
            _ if middle < end => k_a + 1,
            Some(next_row) => next_row.0 - 1,
            None => break,
        };
    }
}

/// The segments j − 1 and j touched by the partners j of one body row (sorted by j, every
/// j ≥ 1 as a partner is a later body), in non-decreasing order: position p stands for
/// segment j_{p/2} − 1 + p mod 2.
struct TouchedSegments<'a> {
    partners: &'a [(usize, usize)],
    position: usize,
}

impl TouchedSegments<'_> {
    /// The segment at the current position, if any.
    fn peek(&self) -> Option<usize> {
        let &(_, j) = self.partners.get(self.position / 2)?;
        Some(j - 1 + self.position % 2)
    }

    /// Moves past the current position, whose segment [`peek`](Self::peek) gave as `segment`,
    /// and returns it.
    fn advance(&mut self, segment: usize) -> usize {
        self.position += 1;
        segment
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// The merged rows give exactly the sorted, unique segment pairs (k_b − k_a at least
        /// the index gap) of segments i − 1, i and j − 1, j over the body pairs (i, j).
        #[test]
        fn segment_pairs_are_those_of_the_body_pairs_sorted_and_unique(
            bodies in 2_usize..60,
            raw in proptest::collection::vec((0_usize..60, 0_usize..60), 0..200),
            index_gap in 0_usize..12,
        ) {
            let index_gap = index_gap.max(1);
            let mut pairs: Vec<(usize, usize)> = raw
                .into_iter()
                .map(|(i, j)| (i % bodies, j % bodies))
                .filter(|&(i, j)| i < j)
                .collect();
            pairs.sort_unstable();
            pairs.dedup();
            let segment_count = bodies - 1;
            let expected: std::collections::BTreeSet<(usize, usize)> = pairs
                .iter()
                .flat_map(|&(i, j)| {
                    let near = |b: usize| [b.checked_sub(1), Some(b)].into_iter().flatten();
                    near(i).flat_map(move |k_a| near(j).map(move |k_b| (k_a, k_b)))
                })
                .filter(|&(k_a, k_b)| k_a + index_gap <= k_b && k_b < segment_count)
                .collect();
            let mut segment_pairs = Vec::new();
            collect_segment_pairs(&pairs, segment_count, index_gap, &mut segment_pairs);
            proptest::prop_assert_eq!(segment_pairs, expected.into_iter().collect::<Vec<_>>());
        }
    }
}
