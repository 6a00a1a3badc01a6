//! The segment pairs waiting for their search, by increasing gap bound.
//!
//! A long chain queues thousands of pairs per crossing (11 400 on the 1000-body knotted
//! state), so each is one integer: its gap bound as a [`total_order_key`] above its index in
//! the pair list. Sorting the integers orders the pairs by gap bound, ties by pair (the list is
//! sorted), several times faster than comparing floating-point fields.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// An unsigned integer in the order of [`f64::total_cmp`]: the bits of a positive number with
/// the sign bit set, those of a negative one inverted.
fn total_order_key(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 { !bits } else { bits | (1 << 63) }
}

/// The number whose [`total_order_key`] is `key`.
fn from_total_order_key(key: u64) -> f64 {
    f64::from_bits(if key >> 63 == 1 { key & !(1 << 63) } else { !key })
}

/// The key of pair (or block) `index` with `gap_bound`: the bound's [`total_order_key`] above
/// the index, so that keys order by bound, then by index.
fn key(gap_bound: f64, index: usize) -> u128 {
    (u128::from(total_order_key(gap_bound)) << 64) | index as u128
}

/// The (gap bound, index) of a [`key`].
fn from_key(key: u128) -> (f64, usize) {
    (from_total_order_key((key >> 64) as u64), key as u64 as usize)
}

/// Segment pairs (or blocks of them) keyed by (gap bound, index in their list), all added
/// first, then sorted.
#[derive(Debug, Clone, Default)]
pub(crate) struct PairQueue {
    keys: Vec<u128>,
}

impl PairQueue {
    /// Room for `pairs` pairs.
    pub(crate) fn reserve(&mut self, pairs: usize) {
        self.keys.reserve(pairs);
    }

    /// Empties the queue.
    pub(crate) fn clear(&mut self) {
        self.keys.clear();
    }

    /// Adds pair `index` of the pair list with its gap bound (cm).
    pub(crate) fn push(&mut self, gap_bound: f64, index: usize) {
        self.keys.push(key(gap_bound, index));
    }

    /// Orders the pairs by gap bound, then by index.
    pub(crate) fn sort(&mut self) {
        self.keys.sort_unstable();
    }

    /// The (gap bound, index) of the pairs, in the queue's order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (f64, usize)> + '_ {
        self.keys.iter().map(|&key| from_key(key))
    }
}

/// Segment pairs keyed as in [`PairQueue`], taken smallest first while more are added (the
/// pairs of the blocks the detector opens).
#[derive(Debug, Clone, Default)]
pub(crate) struct PairHeap {
    keys: BinaryHeap<Reverse<u128>>,
}

impl PairHeap {
    /// Room for `pairs` pairs.
    pub(crate) fn reserve(&mut self, pairs: usize) {
        self.keys.reserve(pairs);
    }

    /// Empties the heap.
    pub(crate) fn clear(&mut self) {
        self.keys.clear();
    }

    /// Adds pair `index` of the pair list with its gap bound (cm).
    pub(crate) fn push(&mut self, gap_bound: f64, index: usize) {
        self.keys.push(Reverse(key(gap_bound, index)));
    }

    /// The (gap bound, index) of the smallest key, if any.
    pub(crate) fn peek(&self) -> Option<(f64, usize)> {
        self.keys.peek().map(|&Reverse(key)| from_key(key))
    }

    /// Removes the smallest key.
    pub(crate) fn pop(&mut self) {
        self.keys.pop();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_order_keys_sort_as_total_cmp() {
        let values = [
            f64::NEG_INFINITY,
            -1e300,
            -2.5,
            -1e-310,
            -0.0,
            0.0,
            1e-310,
            3.0,
            1e300,
            f64::INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        for x in values {
            for y in values {
                assert_eq!(total_order_key(x).cmp(&total_order_key(y)), x.total_cmp(&y), "{x} {y}");
                assert_eq!(from_total_order_key(total_order_key(x)).to_bits(), x.to_bits());
            }
        }
    }

    #[test]
    fn pairs_come_out_by_gap_bound_then_index() {
        let mut queue = PairQueue::default();
        for (gap, index) in [(0.02, 7), (-0.01, 9), (0.02, 3), (-0.0, 1), (0.0, 0)] {
            queue.push(gap, index);
        }
        queue.sort();
        let order: Vec<(f64, usize)> = queue.iter().collect();
        assert_eq!(order, vec![(-0.01, 9), (-0.0, 1), (0.0, 0), (0.02, 3), (0.02, 7)]);
        assert!(order[1].0.is_sign_negative(), "−0 keeps its sign");
        let mut heap = PairHeap::default();
        for (gap, index) in [(0.02, 7), (-0.01, 9), (0.02, 3), (-0.0, 1), (0.0, 0)] {
            heap.push(gap, index);
        }
        let mut popped = Vec::new();
        while let Some(next) = heap.peek() {
            popped.push(next);
            heap.pop();
        }
        assert_eq!(popped, order, "the heap gives the sorted queue's order");
    }
}
