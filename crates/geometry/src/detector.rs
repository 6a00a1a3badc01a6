//! Self-contact detection: broad phase, narrow phase on the spline, merging.

use glam::DVec3;

use crate::broad_phase::{BroadPhase, BroadPhaseOptions};
use crate::centreline::Centreline;
use crate::chord::{chord_distance, closest_chord_parameters};
use crate::cluster::{Candidate, DeepestPerCluster};
use crate::contact::SelfContact;
use crate::coverage::Coverage;
use crate::error::GeometryError;
use crate::narrow_phase::{ClosestPoints, NewtonStatus, closest_points_within_after, search};
use crate::pair_queue::PairQueue;
use crate::sampled_segment::SampledSegments;
use crate::segment_pairs::collect_segment_pairs;

/// The distance below which segments k_a and k_b may be in contact: the largest tube radii
/// along them (a radius along a segment is at most the larger of its two body radii) plus
/// `margin`.
fn reach(radii: &[f64], (k_a, k_b): (usize, usize), margin: f64) -> f64 {
    radii[k_a].max(radii[k_a + 1]) + radii[k_b].max(radii[k_b + 1]) + margin
}

/// A lower bound on the distance of two segments from their chords `a` and `b`, whose closest
/// points are at `chord_parameters`, and their [`crate::Segment::chord_deviation_bound`]s
/// `deviations`: each segment lies within its σ of its chord, so the spline distance is at
/// least d_chord − σ_a − σ_b.
fn distance_lower_bound(
    a: (DVec3, DVec3),
    b: (DVec3, DVec3),
    chord_parameters: [f64; 2],
    deviations: [f64; 2],
) -> f64 {
    chord_distance(a, b, chord_parameters) - deviations[0] - deviations[1]
}

/// Rounding allowance (cm) on a segment pair's gap bound before the records shallower than it
/// count as final: the bound is a difference of distances of a few centimetres, exact to
/// ≈ 1e-15 cm, and the σ it subtracts are upper bounds with room to spare.
const GAP_BOUND_ROUNDING: f64 = 1e-9;

/// Counts of one narrow phase, for its [`DetectionReport`].
#[derive(Debug, Default)]
struct SearchCounts {
    searched: usize,
    covered: usize,
    searched_from_grid: usize,
    newton_failures: usize,
    raw_contacts: usize,
}

/// The cluster radius (in segments) from which segment pairs are searched in order of their
/// gap bounds and skipped when a kept contact covers them (`cluster.rs`). ES103 at 100 bodies
/// has 1.5: there the order covered 1 of 253 pairs and cost 15 µs of an 85 µs narrow phase
/// (keeping 233 records in order), while at 1000 bodies (radius ≈ 16) it covers most pairs
/// near a crossing (2026-11-26, `docs/performance.md`).
const MIN_PRUNING_RADIUS: f64 = 2.0;

/// Options of the [`ContactDetector`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetectorOptions {
    /// Contacts with u_b − u_a ≤ `index_gap` are ignored (default 8): neighbouring parts
    /// of the chain always overlap (see `broad_phase.rs`).
    pub index_gap: usize,
    /// Speculative margin (cm, ≥ 0, default 0.05): a contact is reported when its gap is
    /// below it, so the solver sees it one step before the tubes touch.
    pub margin: f64,
    /// Records closer than this in both u_a and u_b are one contact (default 1.5).
    pub cluster_radius: f64,
    /// Inflation of the broad-phase spheres (cm, default 0): room on top of the derived
    /// reach, which alone covers every contact within `margin` ([`BroadPhaseOptions`]).
    pub broad_phase_inflation: f64,
}

impl Default for DetectorOptions {
    fn default() -> Self {
        DetectorOptions {
            index_gap: 8,
            margin: 0.05,
            cluster_radius: 1.5,
            broad_phase_inflation: BroadPhaseOptions::default().inflation,
        }
    }
}

/// Counts from one [`ContactDetector::detect`] call, for logging and tests.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DetectionReport {
    /// Body pairs reported by the broad phase.
    pub candidate_pairs: usize,
    /// Distinct segment pairs around the candidate body pairs, k_b − k_a ≥ `index_gap` (no
    /// closer pair can give a record outside the index gap).
    pub segment_pairs: usize,
    /// Segment pairs close enough to touch by the chord bound and searched from their chords'
    /// closest points.
    pub searched: usize,
    /// Segment pairs close enough to touch by the chord bound but not searched: a kept contact
    /// no deeper than their gap bound lies within the cluster radius of all their
    /// parameters, so any record of theirs would be merged into it.
    pub covered: usize,
    /// Of those, the pairs whose first search found no contact and that the seed-grid bound
    /// of [`crate::closest_points_within`] could not rule out: searched again from every
    /// start of [`crate::closest_points`].
    pub searched_from_grid: usize,
    /// Segment pairs whose Newton search did not converge (kept, with their status, if
    /// they are contacts).
    pub newton_failures: usize,
    /// Records within the margin before merging.
    pub raw_contacts: usize,
    /// Records merged into another record of the same cluster.
    pub merged: usize,
    /// Contacts written to the output.
    pub contacts: usize,
}

/// Pairs per body that [`ContactDetector::reserve`] makes room for: a body of a tube that does
/// not interpenetrate itself is near far fewer (about 10 in a tight knot) other bodies.
pub const PAIRS_PER_BODY: usize = 64;

/// Self-contact detector: options plus the reusable broad- and narrow-phase workspaces.
///
/// Per call: the broad phase proposes body pairs (with an index gap two less than
/// `index_gap`, so that no pair whose spline parameters differ by more than `index_gap`
/// is lost); the segments touching each body ({i−1, i} × {j−1, j}, deduplicated) that can
/// touch by the chord bound are searched for their closest points; records with
/// gap < margin and u_b − u_a > index_gap are kept, and duplicates merged (see
/// `cluster.rs`: this also drops a closest point clamped to a segment end that is the
/// same point as the neighbouring segment's result). No allocation after warm-up.
///
/// A pair is searched first from its chords' closest points alone. If that search converges
/// to a contact, the pair is a contact there; only otherwise is it searched from every start
/// of [`crate::closest_points`] (if the seed-grid bound cannot rule it out). The other starts
/// exist to find the deepest of several minima of one pair, and a pair that is a contact is
/// nearly always one of a block of neighbouring pairs that see one crossing, of which only the
/// deepest record is kept: so no contact is missed, and the kept records are as deep as with
/// every start on every pair (`crates/run/tests/integration/self_contact.rs`: within 1e-13 cm along
/// the tangled trajectory of `form.ron`), for ≈ 1/7 of the searches (`docs/performance.md`).
#[derive(Debug, Clone)]
pub struct ContactDetector {
    options: DetectorOptions,
    broad_phase: BroadPhase,
    body_pairs: Vec<(usize, usize)>,
    /// Every segment's chord deviation bound σ_k (filled when some pair is to be bounded).
    deviations: Vec<f64>,
    /// The searched segments with their seed-grid samples, made when first searched.
    segments: SampledSegments,
    segment_pairs: Vec<(usize, usize)>,
    /// The segment pairs that may touch, by gap bound (where pairs are searched in that order).
    queue: PairQueue,
    clusters: DeepestPerCluster,
    /// The pairs that the kept records cover, marked as each is kept.
    coverage: Coverage,
    /// Whether pairs are searched by gap bound and skipped when covered: the cluster radius
    /// is at least [`MIN_PRUNING_RADIUS`].
    prune: bool,
}

impl ContactDetector {
    /// Creates a detector with validated options.
    ///
    /// # Errors
    /// [`GeometryError::InvalidOption`] if the margin, cluster radius or inflation is
    /// negative or not finite.
    pub fn new(options: DetectorOptions) -> Result<Self, GeometryError> {
        GeometryError::require_non_negative(&[
            ("margin", options.margin),
            ("cluster_radius", options.cluster_radius),
        ])?;
        let broad_phase = BroadPhase::new(BroadPhaseOptions {
            index_gap: options.index_gap.saturating_sub(2),
            inflation: options.broad_phase_inflation,
            margin: options.margin,
        })?;
        Ok(ContactDetector {
            options,
            broad_phase,
            body_pairs: Vec::new(),
            deviations: Vec::new(),
            segments: SampledSegments::default(),
            segment_pairs: Vec::new(),
            queue: PairQueue::default(),
            clusters: DeepestPerCluster::default(),
            coverage: Coverage::default(),
            prune: options.cluster_radius >= MIN_PRUNING_RADIUS,
        })
    }

    /// Reserves the scratch buffers for a centreline of `bodies` bodies, so that detection
    /// does not allocate: room for [`PAIRS_PER_BODY`] pairs per body in every pair list (a
    /// packing bound for tubes that do not interpenetrate, with room to spare).
    pub fn reserve(&mut self, bodies: usize) {
        let pairs = PAIRS_PER_BODY * bodies;
        self.body_pairs.reserve(pairs);
        self.deviations.reserve(bodies + 1);
        self.segments.reserve(bodies + 1);
        self.segment_pairs.reserve(pairs);
        self.queue.reserve(pairs);
        self.clusters.reserve(pairs);
        self.coverage.reserve(pairs);
    }

    /// Changes the cluster radius (as [`DetectorOptions::cluster_radius`]) without rebuilding
    /// the detector: the runner retries a rejected step with records kept at the chain's own
    /// resolution (`hagfish_sim::StepOptions::resolved_cluster_radius`).
    ///
    /// # Errors
    /// [`GeometryError::InvalidOption`] if `radius` is negative or not finite; the detector
    /// is then unchanged.
    pub fn set_cluster_radius(&mut self, radius: f64) -> Result<(), GeometryError> {
        GeometryError::require_non_negative(&[("cluster_radius", radius)])?;
        self.options.cluster_radius = radius;
        self.prune = radius >= MIN_PRUNING_RADIUS;
        Ok(())
    }

    /// The options this detector uses.
    pub fn options(&self) -> &DetectorOptions {
        &self.options
    }

    /// Fills `out` with the self contacts of `centreline`, sorted by (u_a, u_b): the broad
    /// phase ([`ContactDetector::find_candidates`]), then the narrow phase
    /// ([`ContactDetector::search_candidates`]).
    ///
    /// `body_lengths` are the body lengths ℓ_i (cm) for the broad-phase spheres.
    ///
    /// # Errors
    /// As [`BroadPhase::find_pairs`]; `out` is cleared first.
    pub fn detect(
        &mut self,
        centreline: &Centreline,
        body_lengths: &[f64],
        out: &mut Vec<SelfContact>,
    ) -> Result<DetectionReport, GeometryError> {
        out.clear();
        self.find_candidates(centreline, body_lengths)?;
        Ok(self.search_candidates(centreline, out))
    }

    /// Broad phase: the body pairs whose spheres overlap, and the segment pairs around them.
    ///
    /// # Errors
    /// As [`BroadPhase::find_pairs`].
    pub fn find_candidates(
        &mut self,
        centreline: &Centreline,
        body_lengths: &[f64],
    ) -> Result<(), GeometryError> {
        self.broad_phase.find_pairs(centreline, body_lengths, &mut self.body_pairs)?;
        // A record of segments k_a < k_b has u_b − u_a ≤ k_b + 1 − k_a, so it is outside the
        // index gap only if k_b − k_a ≥ `index_gap`: closer pairs (the broad phase's gap is two
        // less) are never searched.
        let min_offset = self.options.index_gap.max(1);
        let segment_count = centreline.segment_count();
        collect_segment_pairs(&self.body_pairs, segment_count, min_offset, &mut self.segment_pairs);
        Ok(())
    }

    /// Narrow phase on the segment pairs of the last [`ContactDetector::find_candidates`]
    /// (for the same `centreline`): closest points of the pairs that can touch by the chord
    /// bound, records within the margin, duplicates merged; appends the contacts to `out`.
    pub fn search_candidates(
        &mut self,
        centreline: &Centreline,
        out: &mut Vec<SelfContact>,
    ) -> DetectionReport {
        // The bounds read only the centres and σ (compact arrays: on a long chain a crossing
        // is bounded for thousands of segment pairs); a segment is sampled for the seed grid
        // when a search first needs it.
        self.segments.clear(centreline.segment_count());
        if self.segment_pairs.is_empty() {
            self.deviations.clear();
        } else {
            centreline.chord_deviation_bounds(&mut self.deviations);
        }
        let (margin, index_gap) = (self.options.margin, self.options.index_gap as f64);
        // A search result as a contact candidate: within the margin and outside the
        // chain-index exclusion.
        let candidate = |(k_a, k_b): (usize, usize), closest: ClosestPoints| {
            let u_a = k_a as f64 + closest.s_a;
            let u_b = k_b as f64 + closest.s_b;
            let radii = centreline.radius(u_a) + centreline.radius(u_b);
            let gap = closest.distance_squared.sqrt() - radii;
            (gap < margin && u_b - u_a > index_gap).then_some(Candidate {
                u_a,
                u_b,
                gap,
                status: closest.status,
            })
        };
        // Searches one pair from its chords' closest points (then from every start if that
        // finds no contact and the seed grid cannot rule one out) and keeps its record.
        let mut counts = SearchCounts::default();
        let segments = &mut self.segments;
        let mut search_pair =
            |clusters: &mut DeepestPerCluster, pair: (usize, usize), reach, chord| {
                counts.searched += 1;
                let (a, b) = segments.pair(centreline, pair);
                let first = search(&a.segment, &b.segment, chord);
                let found = match candidate(pair, first) {
                    Some(found) if first.status == NewtonStatus::Converged => Some(found),
                    _ => closest_points_within_after(a, b, first, reach).and_then(|closest| {
                        counts.searched_from_grid += 1;
                        counts.newton_failures +=
                            usize::from(closest.status != NewtonStatus::Converged);
                        candidate(pair, closest)
                    }),
                };
                if let Some(found) = found {
                    counts.raw_contacts += 1;
                    clusters.push(found);
                }
            };
        // The pairs that may touch by the chord bound: searched at once in pair order, or,
        // where the cluster radius leaves room to skip some, queued and searched by increasing
        // gap bound, so that every record shallower than the next pair's bound is known and a
        // pair whose records a kept one would merge is skipped (`cluster.rs`).
        let prune = self.prune;
        self.clusters.clear(self.options.cluster_radius);
        self.queue.clear();
        let centres = centreline.centres();
        let chord_of = |k: usize| (centres[k], centres[k + 1]);
        for (index, &pair) in self.segment_pairs.iter().enumerate() {
            let reach = reach(centreline.radii(), pair, margin);
            let (a, b) = (chord_of(pair.0), chord_of(pair.1));
            let chord = closest_chord_parameters(a, b);
            let deviations = [self.deviations[pair.0], self.deviations[pair.1]];
            let distance_bound = distance_lower_bound(a, b, chord, deviations);
            if distance_bound >= reach {
                continue;
            }
            if prune {
                let gap_bound = distance_bound - (reach - margin);
                self.queue.push(gap_bound, index);
            } else {
                search_pair(&mut self.clusters, pair, reach, chord);
            }
        }
        self.queue.sort();
        if !self.queue.is_empty() {
            self.coverage.reset(self.segment_pairs.len());
        }
        let (mut marked, mut covered) = (0, 0);
        for (gap_bound, index) in self.queue.iter() {
            self.clusters.settle_below(gap_bound - GAP_BOUND_ROUNDING);
            for record in &self.clusters.kept()[marked..] {
                self.coverage.mark(&self.segment_pairs, record, self.options.cluster_radius);
            }
            marked = self.clusters.kept().len();
            if self.coverage.is_covered(index) {
                covered += 1;
            } else {
                // Reach and chord parameters again (the same numbers): few pairs get here.
                let pair = self.segment_pairs[index];
                let reach = reach(centreline.radii(), pair, margin);
                let chord = closest_chord_parameters(chord_of(pair.0), chord_of(pair.1));
                search_pair(&mut self.clusters, pair, reach, chord);
            }
        }
        counts.covered = covered;
        let (kept, merged) = self.clusters.finish();
        let before = out.len();
        out.extend(kept.iter().map(|c| SelfContact::new(centreline, c.u_a, c.u_b, c.status)));
        DetectionReport {
            candidate_pairs: self.body_pairs.len(),
            segment_pairs: self.segment_pairs.len(),
            searched: counts.searched,
            covered: counts.covered,
            searched_from_grid: counts.searched_from_grid,
            newton_failures: counts.newton_failures,
            raw_contacts: counts.raw_contacts,
            merged,
            contacts: out.len() - before,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two straight strands of a coarse chain (ℓ = 2 cm, r = 0.9 cm) crossing at right angles
    /// 0.5 cm apart (tube to tube), the contact points at the middle of a segment on both:
    /// their nearest centres are 2.70 cm apart, farther than the bodies' own spheres reach
    /// (2 × 1.345 cm) without inflation. With a margin of 0.6 cm the contact is found all the
    /// same: the spheres reach half a chord, the radius and half the margin.
    #[test]
    fn a_contact_within_the_margin_is_found_without_inflation() {
        let strand_a = (0..10).map(|k| DVec3::new(-9.0 + 2.0 * k as f64, 0.0, 0.0));
        let to_b = (1..7).map(|k| {
            let t = k as f64 / 7.0;
            DVec3::new(9.0 * (1.0 - t), -9.0 * t, 2.3 * t)
                + DVec3::new(3.0, -3.0, 0.0) * (t * (1.0 - t) * 4.0)
        });
        let strand_b = (0..10).map(|k| DVec3::new(0.0, -9.0 + 2.0 * k as f64, 2.3));
        let centres: Vec<DVec3> = strand_a.chain(to_b).chain(strand_b).collect();
        let radii = vec![0.9; centres.len()];
        let line = Centreline::new(&centres, &radii).expect("valid");
        let options = DetectorOptions {
            margin: 0.6,
            broad_phase_inflation: 0.0,
            ..DetectorOptions::default()
        };
        let mut detector = ContactDetector::new(options).expect("valid");
        let mut contacts = Vec::new();
        detector.detect(&line, &vec![2.0; centres.len()], &mut contacts).expect("detects");
        let crossing = contacts.iter().find(|c| c.u_a < 10.0 && c.u_b > 15.0);
        let crossing = crossing.expect("the crossing is a contact");
        assert!((crossing.gap - 0.5).abs() < 1e-6, "gap {}", crossing.gap);
        assert!((crossing.u_a - 4.5).abs() < 1e-6 && (crossing.u_b - 20.5).abs() < 1e-6);
    }
    use glam::DVec3;

    /// Centres one `spacing` apart (by chord) along the curve (2(t² − 1), t(t² − 1), 0.25t),
    /// t ∈ [−1.8, 1.8], which crosses itself at t = ±1 with the strands 0.5 cm apart in z.
    fn alpha_curve(spacing: f64) -> Vec<DVec3> {
        let curve = |t: f64| DVec3::new(2.0 * (t * t - 1.0), t * (t * t - 1.0), 0.25 * t);
        let mut centres = vec![curve(-1.8)];
        for i in 1..=200_000 {
            let p = curve(-1.8 + 3.6 * f64::from(i) / 200_000.0);
            if centres.last().is_some_and(|last| last.distance(p) >= spacing) {
                centres.push(p);
            }
        }
        centres
    }

    #[test]
    fn one_crossing_gives_one_contact_with_normal_from_a_to_b() {
        let centres = alpha_curve(0.424);
        let n = centres.len();
        let line = Centreline::new(&centres, &vec![0.3; n]).expect("valid");
        let mut detector = ContactDetector::new(DetectorOptions::default()).expect("valid");
        let mut contacts = Vec::new();
        let report = detector.detect(&line, &vec![0.424; n], &mut contacts).expect("valid");
        assert_eq!(contacts.len(), 1, "{report:?}: {contacts:#?}");
        assert!(
            report.merged + report.covered > 0,
            "neighbouring segment pairs see the same crossing"
        );
        let contact = &contacts[0];
        assert!((contact.distance - 0.5).abs() < 0.01, "{contact:?}");
        assert!((contact.gap - (contact.distance - 0.6)).abs() < 1e-12);
        assert!(contact.normal.dot(DVec3::Z) > 0.95, "a is at z < 0, b at z > 0");
        // Interior closest points: the normal is perpendicular to both strands.
        assert!(contact.normal.dot(contact.tangent_a).abs() < 1e-9);
        assert!(contact.normal.dot(contact.tangent_b).abs() < 1e-9);
        assert!(contact.point_a.z < 0.0 && contact.point_b.z > 0.0);
        assert_eq!(contact.status, NewtonStatus::Converged);
    }

    /// Skipping the pairs a kept contact covers leaves the contacts exactly as searching every
    /// pair does, on fine chains (bodies 0.03–0.07 cm long in a tube of radius 0.26–0.31 cm,
    /// cluster radius 8 segments) that cross themselves.
    #[test]
    fn skipping_covered_pairs_keeps_the_contacts_bit_for_bit() {
        for (spacing, radius) in [(0.05, 0.3), (0.03, 0.26), (0.07, 0.31)] {
            let centres = alpha_curve(spacing);
            let n = centres.len();
            let line = Centreline::new(&centres, &vec![radius; n]).expect("valid");
            let options = DetectorOptions {
                index_gap: 40,
                cluster_radius: 8.0,
                ..DetectorOptions::default()
            };
            let mut pruned = ContactDetector::new(options).expect("valid");
            let mut every = ContactDetector::new(options).expect("valid");
            every.prune = false;
            let (mut with, mut without) = (Vec::new(), Vec::new());
            let lengths = vec![spacing; n];
            let report = pruned.detect(&line, &lengths, &mut with).expect("valid");
            let reference = every.detect(&line, &lengths, &mut without).expect("valid");
            assert!(report.covered > 0 && reference.covered == 0, "{report:?}");
            assert!(report.searched < reference.searched, "{report:?} {reference:?}");
            assert!(!with.is_empty(), "the crossing is a contact");
            assert_eq!(with, without, "spacing {spacing}");
        }
    }

    #[test]
    fn margin_makes_contacts_speculative() {
        let centres = alpha_curve(0.424);
        let n = centres.len();
        // Tubes of radius 0.24 leave a gap of ≈ 0.02 cm: reported only with the margin.
        let line = Centreline::new(&centres, &vec![0.24; n]).expect("valid");
        let mut contacts = Vec::new();
        for (margin, expected) in [(0.05, 1), (0.0, 0)] {
            let options = DetectorOptions { margin, ..DetectorOptions::default() };
            let mut detector = ContactDetector::new(options).expect("valid");
            detector.detect(&line, &vec![0.424; n], &mut contacts).expect("valid");
            assert_eq!(contacts.len(), expected, "margin {margin}");
        }
    }

    #[test]
    fn invalid_options_are_rejected() {
        let bad = [
            DetectorOptions { margin: -0.1, ..DetectorOptions::default() },
            DetectorOptions { cluster_radius: f64::NAN, ..DetectorOptions::default() },
            DetectorOptions { broad_phase_inflation: f64::INFINITY, ..DetectorOptions::default() },
        ];
        for options in bad {
            assert!(
                matches!(ContactDetector::new(options), Err(GeometryError::InvalidOption { .. })),
                "{options:?}"
            );
        }
        let mut detector = ContactDetector::new(DetectorOptions::default()).expect("detector");
        for radius in [-1.0, f64::NAN] {
            let rejected = detector.set_cluster_radius(radius);
            assert!(matches!(rejected, Err(GeometryError::InvalidOption { .. })), "{radius}");
            assert_eq!(detector.options(), &DetectorOptions::default());
        }
        detector.set_cluster_radius(4.0).expect("a valid radius");
        assert_eq!(detector.options().cluster_radius, 4.0);
    }
}
