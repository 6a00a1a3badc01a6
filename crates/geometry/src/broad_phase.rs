//! Broad phase: body pairs whose bounding spheres overlap.
//!
//! Body i is bounded by a parry3d sphere at c_i of radius
//! `ρ_i = max(√(r_i² + (ℓ_i/2)²) + δ, R_i + m/2)`: √(r² + (ℓ/2)²) covers the disc-shaped body
//! (a cylinder of radius r and length ℓ, whose rim lies that far from its centre) and δ is
//! the caller's inflation; `R_i + m/2` is derived, so that no contact within the speculative
//! margin m can be missed whatever δ is. A contact point on the spline segment k (between
//! c_k and c_{k+1}) lies within half the chord `|c_{k+1} − c_k|/2` of the nearer centre
//! along the chord, plus the segment's deviation from its chord σ_k
//! ([`crate::Segment::chord_deviation_bound`]); the tube there has radius at most
//! `max(r_k, r_{k+1})`; two such points closer than their radii plus m have nearer centres
//! within `R_i + R_j + m` (triangle inequality), with
//! `R_i = max over the segments at c_i of (|c_{k+1} − c_k|/2 + σ_k + max(r_k, r_{k+1}))`.
//! Pairs closer than the index gap along the chain are skipped first, since a straight
//! chain already "touches" itself up to ~4 bodies away (adjacent discs of radius r
//! spaced ℓ ≪ r overlap).
//!
//! The pairs are found through a hierarchy along the chain: runs of [`BLOCK`] consecutive
//! bodies are bounded by one sphere each, and pairs of neighbouring runs, pairs of those and
//! so on by one sphere each (a binary tree over the runs, built bottom-up in O(runs)). A run's
//! partners are searched from the top of the tree down, into the nodes whose sphere overlaps
//! the run's, that hold runs from this one on, and whose last body is farther along the chain
//! than the index gap; a pair of runs is looked into only if their spheres overlap. A chain is
//! spatially coherent, so a free chain visits O(log runs) nodes per run: at 10 000 bodies
//! ≈ 10⁴ sphere tests instead of the ≈ 2·10⁵ of all run pairs, or the 5·10⁷ of all body
//! pairs. Within a partner run a body is tested against the spheres of its [`QUAD`]s of
//! consecutive bodies first, and against their bodies only where those overlap: a run always
//! overlaps its neighbours along the chain, but most of their bodies lie beyond a body's
//! reach (a straight chain of 10 000 bodies tested ≈ 2·10⁵ body pairs without them). The tree
//! visits the runs in order, so the pairs come out sorted by i, then j, without a sort.

use parry3d_f64::bounding_volume::{BoundingSphere, BoundingVolume};

use crate::centreline::Centreline;
use crate::error::GeometryError;

/// Options of the [`BroadPhase`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BroadPhaseOptions {
    /// Pairs (i, j) are reported only when j − i > `index_gap` (default 8).
    pub index_gap: usize,
    /// Inflation δ added to every body's own sphere (cm, ≥ 0, default 0): room the caller
    /// wants on top. Contacts within `margin` are covered whatever δ is (module docs), so
    /// δ only adds pairs that cannot touch: at 1000 bodies of ES103 (bodies 0.04 cm long in
    /// a tube of radius ≈ 0.9 cm) 0.25 cm of it made the detector test ≈ 7 times the segment
    /// pairs it needs around a crossing.
    pub inflation: f64,
    /// The speculative margin m of the contacts the pairs are searched for (cm, ≥ 0,
    /// default 0.05): the spheres reach at least m/2 beyond every spline point's tube.
    pub margin: f64,
}

impl Default for BroadPhaseOptions {
    fn default() -> Self {
        BroadPhaseOptions { index_gap: 8, inflation: 0.0, margin: 0.05 }
    }
}

/// Consecutive bodies bounded together by one sphere (module docs).
const BLOCK: usize = 16;

/// Consecutive bodies bounded together inside a run, tested before their bodies (module docs);
/// a divisor of [`BLOCK`], so a run holds whole quads.
const QUAD: usize = 4;

/// Rounding allowance on a group's sphere radius, relative to the radius and the centre's
/// largest coordinate (the scale of the rounding in its distances), so that every body sphere
/// lies inside its group's sphere as computed: a body pair is then skipped only where its own
/// test would fail, and the pairs are exactly those of the body tests alone.
const RADIUS_ROUNDING: f64 = 1e-9;

/// Broad-phase workspace: the per-body and per-run bounding spheres, reused across calls.
#[derive(Debug, Clone)]
pub struct BroadPhase {
    options: BroadPhaseOptions,
    spheres: Vec<BoundingSphere>,
    /// The tree over the runs: `levels[0]` has one sphere per run of [`BLOCK`] consecutive
    /// bodies, holding their spheres; `levels[k][i]` holds `levels[k − 1][2i]` and
    /// `[2i + 1]`; the last level has one sphere.
    levels: Vec<Vec<BoundingSphere>>,
    /// One sphere per [`QUAD`] consecutive bodies, holding their spheres.
    quads: Vec<BoundingSphere>,
    /// The runs that may hold partners of the run being searched.
    partner_runs: Vec<usize>,
    /// Per segment k: `|c_{k+1} − c_k|/2 + σ_k + max(r_k, r_{k+1})` (module docs).
    reaches: Vec<f64>,
}

impl BroadPhase {
    /// Creates a broad phase with validated options.
    ///
    /// # Errors
    /// [`GeometryError::InvalidOption`] if the inflation is negative or not finite.
    pub fn new(options: BroadPhaseOptions) -> Result<Self, GeometryError> {
        GeometryError::require_non_negative(&[
            ("inflation", options.inflation),
            ("margin", options.margin),
        ])?;
        Ok(BroadPhase {
            options,
            spheres: Vec::new(),
            levels: Vec::new(),
            quads: Vec::new(),
            partner_runs: Vec::new(),
            reaches: Vec::new(),
        })
    }

    /// The options this broad phase was built with.
    pub fn options(&self) -> &BroadPhaseOptions {
        &self.options
    }

    /// Fills `out` with every body pair (i, j), i < j, j − i > index gap, whose inflated
    /// bounding spheres overlap, sorted by (i, j).
    ///
    /// `body_lengths` are the body lengths ℓ_i (cm, one per body). Allocates only on the
    /// first call or when the body count or the number of pairs grows.
    ///
    /// # Errors
    /// [`GeometryError`] if `body_lengths` has the wrong length or a negative or
    /// non-finite entry.
    pub fn find_pairs(
        &mut self,
        centreline: &Centreline,
        body_lengths: &[f64],
        out: &mut Vec<(usize, usize)>,
    ) -> Result<(), GeometryError> {
        GeometryError::require_length("body_lengths", centreline.body_count(), body_lengths.len())?;
        if let Some((index, &value)) =
            body_lengths.iter().enumerate().find(|(_, l)| !(l.is_finite() && **l >= 0.0))
        {
            return Err(GeometryError::InvalidBodyLength { index, value });
        }
        let (inflation, half_margin) = (self.options.inflation, 0.5 * self.options.margin);
        let (centres, radii) = (centreline.centres(), centreline.radii());
        centreline.chord_deviation_bounds(&mut self.reaches);
        for (k, reach) in self.reaches.iter_mut().enumerate() {
            let chord = centres[k].distance(centres[k + 1]);
            *reach = 0.5 * chord + *reach + radii[k].max(radii[k + 1]);
        }
        let reaches = &self.reaches;
        self.spheres.clear();
        self.spheres.extend(centres.iter().zip(radii).zip(body_lengths).enumerate().map(
            |(i, ((&c, &r), &l))| {
                let before = i.checked_sub(1).and_then(|k| reaches.get(k)).copied();
                let reach = before.into_iter().chain(reaches.get(i).copied()).fold(r, f64::max);
                let own = (r * r + 0.25 * l * l).sqrt() + inflation;
                BoundingSphere::new(c, own.max(reach + half_margin))
            },
        ));
        self.build_levels();
        out.clear();
        let (gap, spheres, quads, n) =
            (self.options.index_gap, &self.spheres, &self.quads, self.spheres.len());
        let top = self.levels.len().saturating_sub(1);
        for (a, run_a) in self.levels[0].iter().enumerate() {
            let (first_a, end_a) = (a * BLOCK, ((a + 1) * BLOCK).min(n));
            // The runs from this one on that may hold a partner: some pair of the two runs
            // is farther apart than the index gap, and their spheres overlap.
            self.partner_runs.clear();
            let search =
                RunSearch { levels: &self.levels, bodies: n, gap, run: a, run_sphere: run_a };
            search.collect(top, 0, &mut self.partner_runs);
            // Body by body, partner runs and their quads in order: the pairs come out sorted
            // by (i, j).
            for i in first_a..end_a {
                let first = i.saturating_add(gap).saturating_add(1);
                for &b in &self.partner_runs {
                    let run_quads = b * (BLOCK / QUAD)..((b + 1) * (BLOCK / QUAD)).min(quads.len());
                    for (q, quad) in run_quads.clone().zip(&quads[run_quads]) {
                        let partners = (q * QUAD).max(first)..((q + 1) * QUAD).min(n);
                        if partners.is_empty() || !spheres[i].intersects(quad) {
                            continue;
                        }
                        let touching = partners.filter(|&j| spheres[i].intersects(&spheres[j]));
                        out.extend(touching.map(|j| (i, j)));
                    }
                }
            }
        }
        Ok(())
    }

    /// Fills the quads and the tree over the runs from the bodies' spheres (`quads` and
    /// `levels`, see their fields).
    fn build_levels(&mut self) {
        let runs = self.spheres.len().div_ceil(BLOCK).max(1);
        let depth = runs.next_power_of_two().trailing_zeros() as usize + 1;
        self.quads.clear();
        self.quads.extend(self.spheres.chunks(QUAD).map(holding));
        self.levels.resize_with(depth, Vec::new);
        let (first, rest) = self.levels.split_at_mut(1);
        first[0].clear();
        first[0].extend(self.spheres.chunks(BLOCK).map(holding));
        let mut below = &first[0];
        for level in rest.iter_mut() {
            level.clear();
            level.extend(below.chunks(2).map(|pair| match pair {
                [left, right] => left.merged(right),
                single => single[0],
            }));
            below = level;
        }
    }
}

/// A sphere holding `spheres` (consecutive bodies): at their mean centre, its radius the
/// farthest reach of theirs from it, with [`RADIUS_ROUNDING`].
fn holding(spheres: &[BoundingSphere]) -> BoundingSphere {
    let centre = spheres.iter().map(|s| s.center).sum::<glam::DVec3>() / spheres.len() as f64;
    let reach = spheres.iter().map(|s| s.center.distance(centre) + s.radius).fold(0.0, f64::max);
    let allowance = RADIUS_ROUNDING * (reach + centre.abs().max_element());
    BoundingSphere::new(centre, reach + allowance)
}

/// The search of one run's partner runs down the tree over the runs.
struct RunSearch<'a> {
    levels: &'a [Vec<BoundingSphere>],
    /// The number of bodies.
    bodies: usize,
    /// The index gap.
    gap: usize,
    /// The run whose partners are sought.
    run: usize,
    /// Its sphere.
    run_sphere: &'a BoundingSphere,
}

impl RunSearch<'_> {
    /// Pushes onto `out`, in order, the runs under node `index` of `level` that are this run
    /// or after it, hold a body farther than the gap from the run's first body, and whose
    /// sphere overlaps the run's.
    fn collect(&self, level: usize, index: usize, out: &mut Vec<usize>) {
        let Some(node) = self.levels[level].get(index) else { return };
        let (first_run, end_run) = (index << level, (index + 1) << level);
        let last_body = (end_run * BLOCK).min(self.bodies) - 1;
        let reaches_past_gap =
            last_body.checked_sub(self.run * BLOCK).is_some_and(|d| d > self.gap);
        if end_run <= self.run || !reaches_past_gap || !self.run_sphere.intersects(node) {
            return;
        }
        if level == 0 {
            out.push(first_run);
        } else {
            self.collect(level - 1, 2 * index, out);
            self.collect(level - 1, 2 * index + 1, out);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use proptest::prelude::*;

    fn straight_chain(n: usize) -> Centreline {
        let centres: Vec<_> = (0..n).map(|k| DVec3::new(0.424 * k as f64, 0.0, 0.0)).collect();
        Centreline::new(&centres, &vec![0.89; n]).expect("valid")
    }

    #[test]
    fn straight_chain_has_no_candidates_beyond_the_gap() {
        let line = straight_chain(100);
        let mut broad = BroadPhase::new(BroadPhaseOptions::default()).expect("valid");
        let mut pairs = vec![(7, 7)];
        broad.find_pairs(&line, &[0.424; 100], &mut pairs).expect("valid");
        assert!(pairs.is_empty());
        // Without the index gap, neighbours overlap.
        let options = BroadPhaseOptions { index_gap: 0, ..BroadPhaseOptions::default() };
        let mut broad = BroadPhase::new(options).expect("valid");
        broad.find_pairs(&line, &[0.424; 100], &mut pairs).expect("valid");
        assert!(pairs.contains(&(0, 1)) && pairs.contains(&(0, 5)) && !pairs.contains(&(0, 6)));
    }

    #[test]
    fn invalid_inputs_are_rejected() {
        let line = straight_chain(4);
        let mut broad = BroadPhase::new(BroadPhaseOptions::default()).expect("valid");
        let mut pairs = Vec::new();
        assert!(matches!(
            broad.find_pairs(&line, &[0.4; 3], &mut pairs),
            Err(GeometryError::LengthMismatch { what: "body_lengths", expected: 4, got: 3 })
        ));
        assert!(matches!(
            broad.find_pairs(&line, &[0.4, -0.1, 0.4, 0.4], &mut pairs),
            Err(GeometryError::InvalidBodyLength { index: 1, .. })
        ));
        let negative = BroadPhaseOptions { inflation: -0.1, ..BroadPhaseOptions::default() };
        assert!(BroadPhase::new(negative).is_err());
    }

    proptest! {
        #[test]
        fn equals_brute_force_over_all_pairs(
            coordinates in prop::collection::vec(-3.0_f64..3.0, 6..600),
            radius in 0.2_f64..1.0,
            length in 0.0_f64..0.8,
            index_gap in 0_usize..40,
            inflation in 0.0_f64..0.5,
            walk in any::<bool>(),
        ) {
            // Scattered points, or a random walk of steps of at most 0.35 (a chain, whose
            // runs of bodies are spatially coherent as the two-level search expects).
            let points = coordinates.chunks_exact(3).map(|c| DVec3::new(c[0], c[1], c[2]));
            let centres: Vec<_> = if walk {
                points.scan(DVec3::ZERO, |at, step| { *at += 0.06 * step; Some(*at) }).collect()
            } else {
                points.collect()
            };
            let n = centres.len();
            let radii: Vec<_> = (0..n).map(|k| radius * (1.0 + 0.1 * (k % 3) as f64)).collect();
            let lengths: Vec<_> = (0..n).map(|k| length * (1.0 + 0.2 * (k % 2) as f64)).collect();
            let line = Centreline::new(&centres, &radii).expect("valid");
            let margin = 0.1;
            let options = BroadPhaseOptions { index_gap, inflation, margin };
            let mut broad = BroadPhase::new(options).expect("valid");
            let mut pairs = Vec::new();
            broad.find_pairs(&line, &lengths, &mut pairs).expect("valid");
            // Half a chord, the sag and the larger radius of segment k, the segments at c_k.
            let segment_reach = |k: usize| {
                0.5 * centres[k].distance(centres[k + 1])
                    + line.segment(k).chord_deviation_bound()
                    + radii[k].max(radii[k + 1])
            };
            let reach = |k: usize| {
                let before = if k > 0 { segment_reach(k - 1) } else { 0.0 };
                let after = if k + 1 < n { segment_reach(k) } else { 0.0 };
                before.max(after) + 0.5 * margin
            };
            let bound = |k: usize| {
                let own = (radii[k].powi(2) + (0.5 * lengths[k]).powi(2)).sqrt() + inflation;
                own.max(reach(k))
            };
            let expected: Vec<_> = (0..n)
                .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
                .filter(|&(i, j)| j - i > index_gap)
                .filter(|&(i, j)| centres[i].distance(centres[j]) <= bound(i) + bound(j))
                .collect();
            prop_assert_eq!(pairs, expected);
        }
    }
}
