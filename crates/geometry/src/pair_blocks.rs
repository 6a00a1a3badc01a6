//! Blocks of segment pairs, bounded and skipped together by the detector's pruning
//! (`detector.rs`, `cluster.rs`).
//!
//! On a long chain each crossing is seen by thousands of segment pairs (1000 bodies: 14 300
//! in the knotted state for 33 kept contacts), and a kept contact covers most of them: their
//! records would all be merged into it. Bounding every pair by its chords before knowing
//! that was the detector's largest cost. The pairs are grouped instead into blocks of G × G
//! segments (G = [`GROUP`] consecutive segments of each strand), and each block is bounded by its
//! groups' chords: every point of a group's spline lies within
//!
//! `σ_G = max_{k ∈ G} (σ_k + max(d(c_k), d(c_{k+1})))`
//!
//! of the chord from the group's first centre to its last (σ_k the segment's own chord
//! deviation bound, d the distance to the group's chord: a segment's chord lies within the
//! larger of its ends' distances, the distance to a line segment being convex), so no record
//! of a pair in the block has a gap below
//!
//! `d(chord_A, chord_B) − σ_A − σ_B − r_A − r_B`
//!
//! (r the widest tube radius along the group). The detector takes a block up in the order of
//! that bound among the pairs' own; if a kept contact then covers the block's whole parameter
//! box, the block is skipped whole, else its pairs are bounded one by one and queued. Every
//! bound is a lower bound of the records it stands for, so what is kept is exactly what
//! searching every pair keeps.

use std::ops::Range;

use glam::DVec3;

use crate::centreline::Centreline;
use crate::chord::{chord_distance, closest_chord_parameters};
use crate::cluster::Candidate;
use crate::coverage::reaches;

/// Segments per group (G): a kept contact must cover a block's whole box for the block to be
/// skipped, and around a crossing the pairs within reach reach about as far as the cluster
/// radius, so only small blocks are covered there. On the 1000-body knotted state (cluster
/// radius 16 segments, 14 300 pairs) blocks of 2 × 2 segments skip 2561 of 2997 (the pairs of
/// the others, 1678, bounded one by one), 4 × 4 skip 499 of 826 (4585 pairs bounded) and
/// 8 × 8 only 31 of 260 (10 631): `cargo bench --bench step -- knotted_1000` took 3.92, 4.01
/// and 4.42 ms a step (2026-11-30).
pub(crate) const GROUP: usize = 2;

/// One group of consecutive segments: its chord, how far its spline may stray from it, and
/// its widest tube radius.
#[derive(Debug, Clone, Copy)]
struct Group {
    chord: (DVec3, DVec3),
    deviation: f64,
    widest: f64,
}

/// A block: the segments of one group of the first strand against one of the second, and
/// where its pairs' indices lie in [`PairBlocks::pairs_of`]'s list.
#[derive(Debug, Clone, Copy)]
struct Block {
    groups: (usize, usize),
    pairs: (usize, usize),
}

/// The blocks of one pair list, with their groups (module docs). Nothing allocates after
/// [`reserve`](Self::reserve).
#[derive(Debug, Clone, Default)]
pub(crate) struct PairBlocks {
    /// Segments of the centreline.
    segments: usize,
    groups: Vec<Group>,
    blocks: Vec<Block>,
    /// The pair list's indices, block by block.
    indices: Vec<usize>,
    /// Scratch per group of the second strand: pairs of the current band, then the next free
    /// place of its block in `indices`; zero outside [`PairBlocks::prepare`].
    counts: Vec<usize>,
    /// Scratch: the groups of the second strand that the current band's pairs touch.
    touched: Vec<usize>,
}

impl PairBlocks {
    /// Room for a centreline of `segments` segments and `pairs` pairs.
    pub(crate) fn reserve(&mut self, segments: usize, pairs: usize) {
        self.groups.reserve(segments);
        self.blocks.reserve(pairs);
        self.indices.reserve(pairs);
        self.counts.reserve(segments);
        self.touched.reserve(segments);
    }

    /// Groups of [`GROUP`] segments of `centreline`, whose segments' chord deviation bounds
    /// are `deviations`, and the blocks of `pairs` (sorted by (k_a, k_b), unique, k_b within
    /// the centreline).
    pub(crate) fn prepare(
        &mut self,
        centreline: &Centreline,
        deviations: &[f64],
        pairs: &[(usize, usize)],
    ) {
        self.segments = centreline.segment_count();
        self.blocks.clear();
        self.groups.clear();
        if pairs.is_empty() {
            // No pair, no block (and the deviation bounds are not computed).
            return;
        }
        self.prepare_groups(centreline, deviations);
        self.indices.clear();
        self.indices.resize(pairs.len(), 0);
        self.counts.clear();
        self.counts.resize(self.groups.len(), 0);
        // Pairs are sorted by k_a, so each band of GROUP rows is a run of the list.
        let mut start = 0;
        while start < pairs.len() {
            let band = pairs[start].0 / GROUP;
            let end = start + pairs[start..].partition_point(|p| p.0 / GROUP == band);
            self.add_band(band, start..end, pairs);
            start = end;
        }
    }

    /// The groups' chords, deviation bounds and widest radii (module docs).
    fn prepare_groups(&mut self, centreline: &Centreline, deviations: &[f64]) {
        let (centres, radii) = (centreline.centres(), centreline.radii());
        for first in (0..self.segments).step_by(GROUP) {
            let end = (first + GROUP).min(self.segments);
            let chord = (centres[first], centres[end]);
            let from_chord = |c: DVec3| {
                let point = (c, c);
                chord_distance(point, chord, closest_chord_parameters(point, chord))
            };
            let (mut deviation, mut widest) = (0.0_f64, 0.0_f64);
            let mut previous = from_chord(centres[first]);
            for k in first..end {
                let next = from_chord(centres[k + 1]);
                deviation = deviation.max(deviations[k] + previous.max(next));
                widest = widest.max(radii[k].max(radii[k + 1]));
                previous = next;
            }
            self.groups.push(Group { chord, deviation, widest });
        }
    }

    /// The blocks of one band of rows (`rows` of `pairs`, all with k_a in group `band`): one
    /// pass counts the pairs per group of the second strand, one places their indices.
    fn add_band(&mut self, band: usize, rows: Range<usize>, pairs: &[(usize, usize)]) {
        self.touched.clear();
        for &(_, k_b) in &pairs[rows.clone()] {
            let group = k_b / GROUP;
            if self.counts[group] == 0 {
                self.touched.push(group);
            }
            self.counts[group] += 1;
        }
        self.touched.sort_unstable();
        let mut next = rows.start;
        for &group in &self.touched {
            let count = self.counts[group];
            self.blocks.push(Block { groups: (band, group), pairs: (next, next + count) });
            // From here on the count is the block's next free place.
            self.counts[group] = next;
            next += count;
        }
        for (index, &(_, k_b)) in pairs.iter().enumerate().take(rows.end).skip(rows.start) {
            let place = &mut self.counts[k_b / GROUP];
            self.indices[*place] = index;
            *place += 1;
        }
        for &group in &self.touched {
            self.counts[group] = 0;
        }
    }

    /// The number of blocks.
    pub(crate) fn len(&self) -> usize {
        self.blocks.len()
    }

    /// A lower bound of the gap (cm) of every record of block `i`'s pairs (module docs), or
    /// `None` where none of its pairs can come within `margin`: the spline distance bound is
    /// beyond the widest reach (radii and margin) of the block.
    pub(crate) fn gap_bound(&self, i: usize, margin: f64) -> Option<f64> {
        let (a, b) = self.blocks[i].groups;
        let (a, b) = (&self.groups[a], &self.groups[b]);
        let chords = closest_chord_parameters(a.chord, b.chord);
        let distance = chord_distance(a.chord, b.chord, chords) - a.deviation - b.deviation;
        let radii = a.widest + b.widest;
        (distance < radii + margin).then_some(distance - radii)
    }

    /// The indices into the pair list of block `i`'s pairs, in the list's order.
    pub(crate) fn pairs_of(&self, i: usize) -> &[usize] {
        let (start, end) = self.blocks[i].pairs;
        &self.indices[start..end]
    }

    /// Whether `record` lies within `radius` of block `i`'s whole parameter box in both
    /// parameters: then every record of its pairs is one that `record` drops.
    pub(crate) fn covered_by(&self, i: usize, record: &Candidate, radius: f64) -> bool {
        let (a, b) = self.blocks[i].groups;
        let (a, b) = (self.span(a), self.span(b));
        reaches(record.u_a, radius, a.start, a.end) && reaches(record.u_b, radius, b.start, b.end)
    }

    /// The parameter interval [first segment, last segment + 1] of group `g`.
    fn span(&self, g: usize) -> Range<f64> {
        let first = g * GROUP;
        first as f64..(first + GROUP).min(self.segments) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A helix of `n` centres 0.2 cm apart by arc, radius 1 cm, pitch 0.5 cm per turn.
    fn helix(n: usize) -> Centreline {
        let centres: Vec<DVec3> = (0..n)
            .map(|i| {
                let t = 0.2 * i as f64;
                DVec3::new(t.cos(), t.sin(), 0.5 * t / std::f64::consts::TAU)
            })
            .collect();
        Centreline::new(&centres, &vec![0.05; n]).expect("a centreline")
    }

    /// The blocks of `pairs` on `line`.
    fn blocks_of(line: &Centreline, pairs: &[(usize, usize)]) -> PairBlocks {
        let mut deviations = Vec::new();
        line.chord_deviation_bounds(&mut deviations);
        let mut blocks = PairBlocks::default();
        blocks.prepare(line, &deviations, pairs);
        blocks
    }

    #[test]
    fn every_pair_lands_in_the_block_of_its_groups_once() {
        let line = helix(60);
        let pairs: Vec<(usize, usize)> =
            (0..59).flat_map(|a| (a + 3..59).step_by(2).map(move |b| (a, b))).collect();
        let blocks = blocks_of(&line, &pairs);
        let mut seen = vec![0; pairs.len()];
        for i in 0..blocks.len() {
            let (a, b) = blocks.blocks[i].groups;
            for &index in blocks.pairs_of(i) {
                seen[index] += 1;
                assert_eq!((pairs[index].0 / GROUP, pairs[index].1 / GROUP), (a, b));
            }
            assert!(blocks.pairs_of(i).windows(2).all(|w| w[0] < w[1]), "in list order");
        }
        assert!(seen.iter().all(|&s| s == 1));
    }

    #[test]
    fn a_block_bounds_every_point_pair_of_its_splines() {
        let line = helix(80);
        let pairs: Vec<(usize, usize)> =
            (0..79).flat_map(|a| (a + 1..79).map(move |b| (a, b))).collect();
        let blocks = blocks_of(&line, &pairs);
        for i in 0..blocks.len() {
            let Some(bound) = blocks.gap_bound(i, f64::INFINITY) else {
                panic!("an infinite margin reaches every block")
            };
            let (a, b) = blocks.blocks[i].groups;
            let (a, b) = (blocks.span(a), blocks.span(b));
            let samples = |r: Range<f64>| {
                (0..=40).map(move |j| r.start + (r.end - r.start) * f64::from(j) / 40.0)
            };
            for u_a in samples(a.clone()) {
                for u_b in samples(b.clone()) {
                    let gap = line.point(u_a).distance(line.point(u_b))
                        - line.radius(u_a)
                        - line.radius(u_b);
                    assert!(gap >= bound - 1e-12, "block {i}: gap {gap} below {bound}");
                }
            }
        }
    }
}
