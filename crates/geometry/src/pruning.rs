//! The pruned narrow phase of fine chains: segment pairs searched by increasing lower bound
//! on their records' gaps and skipped when a kept contact covers them; from a cluster radius
//! of [`MIN_BLOCK_RADIUS`] segments taken in blocks until a block must be opened
//! (`cluster.rs`, `coverage.rs`, `pair_blocks.rs`).
//!
//! Blocks and the pairs of opened blocks come up in one order of their bounds (a block before
//! a pair of the same bound). Before each, every record shallower than its bound (less a
//! rounding allowance) is settled: no record still to come can be shallower, since each has
//! a gap at least its pair's bound and every smaller bound came up already. A block or pair
//! whose whole parameter box lies within the cluster radius of a kept record is skipped:
//! every record of it would be merged into that one. So what is kept is what searching every
//! pair keeps, bit for bit.

use crate::cluster::DeepestPerCluster;
use crate::coverage::{Coverage, covers};
use crate::pair_blocks::PairBlocks;
use crate::pair_queue::{PairHeap, PairQueue};
use crate::searches::{Searches, pair_bound};

/// Rounding allowance (cm) on a gap bound before the records shallower than it count as
/// final: a bound is a difference of distances of a few centimetres, exact to ≈ 1e-15 cm,
/// and the σ it subtracts are upper bounds with room to spare.
const GAP_BOUND_ROUNDING: f64 = 1e-9;

/// The cluster radius (segments) from which pairs are queued in blocks: a block is skipped only
/// when a kept contact covers its whole box, which a short radius seldom does. `hagfish run
/// data/scenarios/tie.ron` with ES103 at N bodies, the mean `check` stage (which detects) in
/// µs, pairs queued one by one against blocks (2026-11-30, two runs each): 300 bodies (radius
/// 4.7) 157–162 against 195–197, 500 (7.9) 252 against 264–271, 700 (11.0) 345–346 against
/// 315–317, 1000 (15.8) 633–639 against 533–536.
const MIN_BLOCK_RADIUS: f64 = 10.0;

/// The reusable buffers of the pruned search.
#[derive(Debug, Clone, Default)]
pub(crate) struct PruningScratch {
    pub(crate) blocks: PairBlocks,
    /// The blocks (at a short cluster radius the pairs) that may touch, by gap bound.
    pub(crate) queue: PairQueue,
    /// The pairs of the opened blocks that may touch, by gap bound.
    pub(crate) heap: PairHeap,
    /// The pairs that the kept records cover, marked as each is kept.
    pub(crate) coverage: Coverage,
}

impl PruningScratch {
    /// Room for a centreline of `segments` segments and `pairs` segment pairs.
    pub(crate) fn reserve(&mut self, segments: usize, pairs: usize) {
        self.blocks.reserve(segments, pairs);
        self.queue.reserve(pairs);
        self.heap.reserve(pairs);
        self.coverage.reserve(pairs);
    }
}

/// What the sorted queue of [`search_by_gap_bound`] holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Queued {
    /// Blocks of pairs, opened into the heap when not covered.
    Blocks,
    /// The pairs themselves (a short cluster radius covers few whole blocks).
    Pairs,
}

/// Searches `pairs` (sorted by (k_a, k_b), unique) in the order of the module docs, with
/// `deviations` the segments' chord deviation bounds and records within `radius` (the cluster
/// radius, in segments) of a kept one merged; returns how many pairs a kept record covered
/// (those of the blocks skipped whole included).
pub(crate) fn search_by_gap_bound(
    searches: &mut Searches<'_>,
    scratch: &mut PruningScratch,
    (pairs, deviations): (&[(usize, usize)], &[f64]),
    radius: f64,
) -> usize {
    let (centreline, margin) = (searches.test.centreline, searches.test.margin);
    let PruningScratch { blocks, queue, heap, coverage } = scratch;
    let queued = if radius >= MIN_BLOCK_RADIUS { Queued::Blocks } else { Queued::Pairs };
    queue.clear();
    match queued {
        Queued::Blocks => {
            blocks.prepare(centreline, deviations, pairs);
            for i in 0..blocks.len() {
                if let Some(bound) = blocks.gap_bound(i, margin) {
                    queue.push(bound, i);
                }
            }
        }
        Queued::Pairs => {
            for (index, &pair) in pairs.iter().enumerate() {
                if let Some(bound) = pair_bound(centreline, deviations, pair, margin) {
                    queue.push(bound.gap, index);
                }
            }
        }
    }
    queue.sort();
    heap.clear();
    if queued == Queued::Pairs {
        coverage.reset(pairs.len());
    }
    let (mut marked, mut covered) = (0, 0);
    // Settles the records below `bound`; queued one by one, the pairs are many, and those the
    // new kept records cover are marked; in blocks, the few pairs of opened blocks ask the kept
    // records themselves.
    let mut settle = |clusters: &mut DeepestPerCluster, bound: f64, coverage: &mut Coverage| {
        clusters.settle_below(bound - GAP_BOUND_ROUNDING);
        if queued == Queued::Pairs {
            for record in &clusters.kept()[marked..] {
                coverage.mark(pairs, record, radius);
            }
            marked = clusters.kept().len();
        }
    };
    let mut next_queued = queue.iter().peekable();
    loop {
        // The smaller bound next; a block before a pair of the same bound.
        let from_queue = match (next_queued.peek(), heap.peek()) {
            (None, None) => break,
            (Some(&(next, _)), Some((pair, _))) => next <= pair,
            (next, _) => next.is_some(),
        };
        let (bound, index) = match (from_queue, queued) {
            (true, Queued::Blocks) => {
                let Some((bound, i)) = next_queued.next() else { break };
                settle(searches.clusters, bound, coverage);
                let kept = searches.clusters.kept();
                if kept.iter().any(|record| blocks.covered_by(i, record, radius)) {
                    covered += blocks.pairs_of(i).len();
                    continue;
                }
                for &index in blocks.pairs_of(i) {
                    if let Some(bound) = pair_bound(centreline, deviations, pairs[index], margin) {
                        heap.push(bound.gap, index);
                    }
                }
                continue;
            }
            (true, Queued::Pairs) => {
                let Some(pair) = next_queued.next() else { break };
                pair
            }
            (false, _) => {
                let Some(pair) = heap.peek() else { break };
                heap.pop();
                pair
            }
        };
        settle(searches.clusters, bound, coverage);
        let is_covered = match queued {
            Queued::Pairs => coverage.is_covered(index),
            Queued::Blocks => {
                searches.clusters.kept().iter().any(|record| covers(record, radius, pairs[index]))
            }
        };
        if is_covered {
            covered += 1;
        } else if let Some(bound) = pair_bound(centreline, deviations, pairs[index], margin) {
            // The same numbers again: few pairs get here.
            searches.search(pairs[index], &bound);
        }
    }
    covered
}
