//! The searches of one narrow phase: a segment pair's chord bound, and its closest-point
//! search kept as a record when it is a contact.

use glam::DVec3;

use crate::centreline::Centreline;
use crate::chord::{chord_distance, closest_chord_parameters};
use crate::cluster::{Candidate, DeepestPerCluster};
use crate::narrow_phase::{ClosestPoints, NewtonStatus, closest_points_within_after, search};
use crate::sampled_segment::SampledSegments;

/// What bounds one segment pair before its search: the distance below which it may touch,
/// its chords' closest parameters (the search's start) and the lower bound of its records'
/// gaps.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairBound {
    /// The tubes' widest radii along both segments plus the margin (cm).
    pub(crate) reach: f64,
    /// The chords' closest points, as local parameters.
    pub(crate) chord: [f64; 2],
    /// No record of the pair has a gap below this (cm).
    pub(crate) gap: f64,
}

/// The bound of segment pair `(k_a, k_b)` of `centreline`, whose segments' chord deviation
/// bounds are `deviations`, or `None` where the pair cannot come within `margin`: each segment
/// lies within its σ of its chord, so the spline distance is at least d_chord − σ_a − σ_b, and
/// a record's gap at least that less the widest radii.
pub(crate) fn pair_bound(
    centreline: &Centreline,
    deviations: &[f64],
    (k_a, k_b): (usize, usize),
    margin: f64,
) -> Option<PairBound> {
    let (centres, radii) = (centreline.centres(), centreline.radii());
    let radii = radii[k_a].max(radii[k_a + 1]) + radii[k_b].max(radii[k_b + 1]);
    let chord_of = |k: usize| -> (DVec3, DVec3) { (centres[k], centres[k + 1]) };
    let (a, b) = (chord_of(k_a), chord_of(k_b));
    let chord = closest_chord_parameters(a, b);
    let distance = chord_distance(a, b, chord) - deviations[k_a] - deviations[k_b];
    let reach = radii + margin;
    (distance < reach).then_some(PairBound { reach, chord, gap: distance - (reach - margin) })
}

/// Counts of one narrow phase, for its `DetectionReport`.
#[derive(Debug, Default)]
pub(crate) struct SearchCounts {
    pub(crate) searched: usize,
    pub(crate) covered: usize,
    pub(crate) searched_from_grid: usize,
    pub(crate) newton_failures: usize,
    pub(crate) raw_contacts: usize,
}

/// What makes a search result on `centreline` a contact candidate: within the margin and
/// outside the chain-index exclusion.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactTest<'a> {
    pub(crate) centreline: &'a Centreline,
    /// Records with a gap below it (cm) are contacts.
    pub(crate) margin: f64,
    /// Records with u_b − u_a at most this are the chain's own neighbours.
    pub(crate) index_gap: f64,
}

impl ContactTest<'_> {
    /// The result `closest` of segment pair `(k_a, k_b)` as a candidate, if it is one.
    fn candidate(&self, (k_a, k_b): (usize, usize), closest: ClosestPoints) -> Option<Candidate> {
        let u_a = k_a as f64 + closest.s_a;
        let u_b = k_b as f64 + closest.s_b;
        let radii = self.centreline.radius(u_a) + self.centreline.radius(u_b);
        let gap = closest.distance_squared.sqrt() - radii;
        (gap < self.margin && u_b - u_a > self.index_gap).then_some(Candidate {
            u_a,
            u_b,
            gap,
            status: closest.status,
        })
    }
}

/// One narrow phase's searches: what counts as a contact, the segments sampled so far, where
/// the records go, and the counts.
pub(crate) struct Searches<'a> {
    pub(crate) test: ContactTest<'a>,
    pub(crate) segments: &'a mut SampledSegments,
    pub(crate) clusters: &'a mut DeepestPerCluster,
    pub(crate) counts: SearchCounts,
}

impl Searches<'_> {
    /// Searches `pair` from its chords' closest points (then from every start if that finds
    /// no contact and the seed grid cannot rule one out) and keeps its record.
    pub(crate) fn search(&mut self, pair: (usize, usize), bound: &PairBound) {
        let test = self.test;
        let counts = &mut self.counts;
        counts.searched += 1;
        let (a, b) = self.segments.pair(test.centreline, pair);
        let first = search(&a.segment, &b.segment, bound.chord);
        let found = match test.candidate(pair, first) {
            Some(found) if first.status == NewtonStatus::Converged => Some(found),
            _ => closest_points_within_after(a, b, first, bound.reach).and_then(|closest| {
                counts.searched_from_grid += 1;
                counts.newton_failures += usize::from(closest.status != NewtonStatus::Converged);
                test.candidate(pair, closest)
            }),
        };
        if let Some(found) = found {
            counts.raw_contacts += 1;
            self.clusters.push(found);
        }
    }
}
