//! A segment together with what every narrow-phase pair it takes part in needs of it.
//!
//! One segment is part of several segment pairs per detection (a crossing is seen by a
//! block of neighbouring pairs, a line contact by a band of them), and each pair's seed
//! grid needs the segment's points and tangents at the grid parameters and its speed bound.
//! The detector computes them once per segment and detection, when a search first needs
//! them, instead of once per pair.

use crate::centreline::Centreline;
use crate::seeds::SEED_GRID_INTERVALS;
use crate::segment::Segment;

/// Samples per parameter of the seed grid: s_i = i / n for i = 0..=n.
pub(crate) const GRID_SAMPLES: usize = SEED_GRID_INTERVALS + 1;

/// A [`Segment`] with its seed-grid samples and speed bound, computed once.
///
/// The samples are stored coordinate by coordinate (`points[c][i]` is coordinate c of
/// x(s_i)), so that the seed grid's inner loop over the second segment's samples reads
/// contiguous arrays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SampledSegment {
    /// The segment itself.
    pub(crate) segment: Segment,
    /// [`Segment::speed_bound`].
    pub(crate) speed_bound: f64,
    /// x(s_i), by coordinate.
    pub(crate) points: [[f64; GRID_SAMPLES]; 3],
    /// x′(s_i), by coordinate.
    pub(crate) tangents: [[f64; GRID_SAMPLES]; 3],
}

impl SampledSegment {
    /// Samples `segment` at the seed-grid parameters and computes its speed bound.
    pub(crate) fn new(segment: Segment) -> SampledSegment {
        let grid = |i: usize| i as f64 / SEED_GRID_INTERVALS as f64;
        let mut points = [[0.0; GRID_SAMPLES]; 3];
        let mut tangents = [[0.0; GRID_SAMPLES]; 3];
        for i in 0..GRID_SAMPLES {
            let (point, tangent) = (segment.point(grid(i)), segment.derivative(grid(i)));
            for c in 0..3 {
                points[c][i] = point[c];
                tangents[c][i] = tangent[c];
            }
        }
        SampledSegment { segment, speed_bound: segment.speed_bound(), points, tangents }
    }
}

/// The [`SampledSegment`]s of one detection, each made when a search first needs it: on a
/// long chain most segments of the pairs near a crossing are never searched (their pairs are
/// bounded out or covered by a kept contact).
#[derive(Debug, Clone, Default)]
pub(crate) struct SampledSegments {
    samples: Vec<SampledSegment>,
    /// Per segment of the centreline, its place in `samples` (`usize::MAX`: not made yet).
    slots: Vec<usize>,
}

impl SampledSegments {
    /// Room for `segments` segments.
    pub(crate) fn reserve(&mut self, segments: usize) {
        self.samples.reserve(segments);
        self.slots.reserve(segments);
    }

    /// Forgets every sample, for a centreline of `segment_count` segments.
    pub(crate) fn clear(&mut self, segment_count: usize) {
        self.samples.clear();
        self.slots.clear();
        self.slots.resize(segment_count, usize::MAX);
    }

    /// Segments `k_a` and `k_b` of `centreline` (the one of the last [`clear`](Self::clear))
    /// with their samples, made now if not yet.
    pub(crate) fn pair(
        &mut self,
        centreline: &Centreline,
        (k_a, k_b): (usize, usize),
    ) -> (&SampledSegment, &SampledSegment) {
        let (a, b) = (self.slot(centreline, k_a), self.slot(centreline, k_b));
        (&self.samples[a], &self.samples[b])
    }

    fn slot(&mut self, centreline: &Centreline, k: usize) -> usize {
        if self.slots[k] == usize::MAX {
            self.slots[k] = self.samples.len();
            self.samples.push(SampledSegment::new(centreline.segment(k)));
        }
        self.slots[k]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn samples_are_the_segment_points_and_tangents_at_the_grid_parameters() {
        let segment = Segment::new([
            DVec3::new(-0.4, 0.1, 0.0),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.4, 0.2, -0.1),
            DVec3::new(0.7, 0.5, 0.1),
        ]);
        let sampled = SampledSegment::new(segment);
        for i in 0..GRID_SAMPLES {
            let s = i as f64 / SEED_GRID_INTERVALS as f64;
            let at = |samples: &[[f64; GRID_SAMPLES]; 3]| {
                DVec3::new(samples[0][i], samples[1][i], samples[2][i])
            };
            assert_eq!(at(&sampled.points), segment.point(s));
            assert_eq!(at(&sampled.tangents), segment.derivative(s));
        }
        assert_eq!(sampled.speed_bound, segment.speed_bound());
    }
}
