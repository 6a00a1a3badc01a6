//! Self-contact detection: broad phase, narrow phase on the spline, merging.

use crate::broad_phase::{BroadPhase, BroadPhaseOptions};
use crate::centreline::Centreline;
use crate::cluster::DeepestPerCluster;
use crate::contact::SelfContact;
use crate::error::GeometryError;
use crate::pruning::{PruningScratch, search_by_gap_bound};
use crate::sampled_segment::SampledSegments;
use crate::searches::{ContactTest, SearchCounts, Searches, pair_bound};
use crate::segment_pairs::collect_segment_pairs;

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
    /// Segment pairs not searched because a kept contact no deeper than their gap bound lies
    /// within the cluster radius of all their parameters, so any record of theirs would be
    /// merged into it: pairs close enough to touch by the chord bound, and every pair of a
    /// block skipped whole (`pair_blocks.rs`, long chains).
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
    clusters: DeepestPerCluster,
    /// The buffers of the search by gap bound (`pruning.rs`).
    pruning: PruningScratch,
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
            clusters: DeepestPerCluster::default(),
            pruning: PruningScratch::default(),
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
        self.clusters.reserve(pairs);
        self.pruning.reserve(bodies + 1, pairs);
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
        let radius = self.options.cluster_radius;
        self.clusters.clear(radius);
        let (margin, index_gap) = (self.options.margin, self.options.index_gap as f64);
        let mut searches = Searches {
            test: ContactTest { centreline, margin, index_gap },
            segments: &mut self.segments,
            clusters: &mut self.clusters,
            counts: SearchCounts::default(),
        };
        // The pairs that may touch by the chord bound: searched at once in pair order, or,
        // where the cluster radius leaves room to skip some, by increasing gap bound, in
        // blocks until a block must be opened (`pruning.rs`).
        let (pairs, deviations) = (&self.segment_pairs[..], &self.deviations[..]);
        if self.prune {
            let scratch = &mut self.pruning;
            searches.counts.covered =
                search_by_gap_bound(&mut searches, scratch, (pairs, deviations), radius);
        } else {
            for &pair in pairs {
                if let Some(bound) = pair_bound(centreline, deviations, pair, margin) {
                    searches.search(pair, &bound);
                }
            }
        }
        let counts = searches.counts;
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
    use crate::NewtonStatus;

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
    /// pair does, on fine chains (bodies 0.02–0.07 cm long in a tube of radius 0.26–0.31 cm)
    /// that cross themselves: pairs queued one by one (cluster radius 8 segments) and in
    /// blocks (16).
    #[test]
    fn skipping_covered_pairs_keeps_the_contacts_bit_for_bit() {
        let cases = [(0.05, 0.3, 8.0), (0.03, 0.26, 8.0), (0.07, 0.31, 8.0), (0.02, 0.3, 16.0)];
        for (spacing, radius, cluster_radius) in cases {
            let centres = alpha_curve(spacing);
            let n = centres.len();
            let line = Centreline::new(&centres, &vec![radius; n]).expect("valid");
            let options =
                DetectorOptions { index_gap: 40, cluster_radius, ..DetectorOptions::default() };
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
            assert_eq!(with, without, "spacing {spacing}, cluster radius {cluster_radius}");
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
