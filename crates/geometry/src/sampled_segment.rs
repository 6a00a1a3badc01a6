//! A segment together with what every narrow-phase pair it takes part in needs of it.
//!
//! One segment is part of several segment pairs per detection (a crossing is seen by a
//! block of neighbouring pairs, a line contact by a band of them), and each pair's seed
//! grid needs the segment's points and tangents at the grid parameters, its speed bound
//! and its chord-deviation bound. The detector computes them once per segment and
//! detection instead of once per pair.

use crate::seeds::SEED_GRID_INTERVALS;
use crate::segment::Segment;

/// Samples per parameter of the seed grid: s_i = i / n for i = 0..=n.
pub(crate) const GRID_SAMPLES: usize = SEED_GRID_INTERVALS + 1;

/// A [`Segment`] with its seed-grid samples and bounds, computed once.
///
/// The samples are stored coordinate by coordinate (`points[c][i]` is coordinate c of
/// x(s_i)), so that the seed grid's inner loop over the second segment's samples reads
/// contiguous arrays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SampledSegment {
    /// The segment itself.
    pub(crate) segment: Segment,
    /// [`Segment::chord_deviation_bound`].
    pub(crate) chord_deviation: f64,
    /// [`Segment::speed_bound`].
    pub(crate) speed_bound: f64,
    /// x(s_i), by coordinate.
    pub(crate) points: [[f64; GRID_SAMPLES]; 3],
    /// x′(s_i), by coordinate.
    pub(crate) tangents: [[f64; GRID_SAMPLES]; 3],
}

impl SampledSegment {
    /// Samples `segment` at the seed-grid parameters and computes its bounds.
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
        SampledSegment {
            segment,
            chord_deviation: segment.chord_deviation_bound(),
            speed_bound: segment.speed_bound(),
            points,
            tangents,
        }
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
        assert_eq!(sampled.chord_deviation, segment.chord_deviation_bound());
    }
}
