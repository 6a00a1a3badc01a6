//! The body centreline: a uniform Catmull-Rom spline through the body centres.
//!
//! Segment k (0..N−2) joins c_k and c_{k+1}; the global parameter is u = k + s with
//! s ∈ [0, 1], so u ∈ [0, N−1] and x(k) = c_k. Phantom end points c₋₁ = 2c₀ − c₁ and
//! c_N = 2c_{N−1} − c_{N−2} close the end segments. The curve is C¹: x″ jumps at integer u,
//! where the segment starting there is used (the last segment at u = N−1).
//! The tube radius r(u) interpolates the body radii linearly in u.

use std::cell::{Cell, Ref, RefCell};

use glam::DVec3;

use crate::arc_length::{invert_segment_length, segment_length};
use crate::error::GeometryError;
use crate::segment::{Segment, basis, basis_derivative, bend, chord_deviation_bound};
use crate::weights::SplineWeights;

/// The Catmull-Rom centreline through the body centres, with the body radii and a
/// cumulative arc-length table.
///
/// It owns copies of the centres and radii so that the narrow phase, the solver's contact
/// Jacobians and the renderer all see one consistent curve per step. Build it once with
/// [`Centreline::new`] and refresh it every step with [`Centreline::update`], which does
/// not allocate while the body count is unchanged.
///
/// The arc-length table is built on the first arc-length query after an update (a quadrature
/// per segment: 5 % of a step of a free chain of 10 000 bodies, where nothing asks for it;
/// the contact predictor's curve is never asked either), into a buffer kept across updates.
#[derive(Debug, Clone)]
pub struct Centreline {
    centres: Vec<DVec3>,
    radii: Vec<f64>,
    /// `cumulative_length[k]` is the arc length from u = 0 to u = k (N entries), valid when
    /// `lengths_current` is set.
    cumulative_length: RefCell<Vec<f64>>,
    /// Whether `cumulative_length` is that of the current centres.
    lengths_current: Cell<bool>,
}

impl Centreline {
    /// Builds the centreline through `centres` with tube radii `radii` (cm), one per body.
    ///
    /// # Errors
    /// [`GeometryError`] if there are fewer than 2 centres, `radii` has another length,
    /// a centre is not finite or a radius is not positive and finite.
    pub fn new(centres: &[DVec3], radii: &[f64]) -> Result<Self, GeometryError> {
        let mut centreline = Centreline {
            centres: Vec::with_capacity(centres.len()),
            radii: Vec::with_capacity(radii.len()),
            cumulative_length: RefCell::new(Vec::with_capacity(centres.len())),
            lengths_current: Cell::new(false),
        };
        centreline.update(centres, radii)?;
        Ok(centreline)
    }

    /// Replaces the centres and radii; the arc-length table is rebuilt when next asked for.
    ///
    /// Validates everything before touching `self`, so on error the previous curve is
    /// kept. Allocates only if the body count grew.
    ///
    /// # Errors
    /// As [`Centreline::new`].
    pub fn update(&mut self, centres: &[DVec3], radii: &[f64]) -> Result<(), GeometryError> {
        validate(centres, radii)?;
        self.centres.clear();
        self.centres.extend_from_slice(centres);
        self.radii.clear();
        self.radii.extend_from_slice(radii);
        self.lengths_current.set(false);
        Ok(())
    }

    /// The cumulative arc-length table of the current centres (N entries), built here if an
    /// update made it stale.
    fn cumulative_length(&self) -> Ref<'_, [f64]> {
        if !self.lengths_current.get() {
            let mut table = self.cumulative_length.borrow_mut();
            table.clear();
            let mut total = 0.0;
            table.push(total);
            for k in 0..self.segment_count() {
                total += segment_length(&self.segment(k), 1.0);
                table.push(total);
            }
            self.lengths_current.set(true);
        }
        Ref::map(self.cumulative_length.borrow(), Vec::as_slice)
    }

    /// Number of bodies N (centres).
    pub fn body_count(&self) -> usize {
        self.centres.len()
    }

    /// Number of segments N − 1; valid global parameters are u ∈ [0, N − 1].
    pub fn segment_count(&self) -> usize {
        self.centres.len() - 1
    }

    /// The body centres c_0..c_{N−1} (cm).
    pub fn centres(&self) -> &[DVec3] {
        &self.centres
    }

    /// The body radii r_0..r_{N−1} (cm).
    pub fn radii(&self) -> &[f64] {
        &self.radii
    }

    /// Splits a global parameter into (segment k, local s): u is clamped to [0, N − 1],
    /// k = ⌊u⌋ except at u = N − 1, which maps to the last segment with s = 1.
    /// A NaN `u` gives segment 0 with s = NaN (and NaN results downstream).
    pub fn locate(&self, u: f64) -> (usize, f64) {
        let last = self.segment_count();
        let u = u.clamp(0.0, last as f64);
        // `u` is in [0, last] (or NaN, which casts to 0), so the cast is exact and safe.
        let k = (u.floor() as usize).min(last - 1);
        (k, u - k as f64)
    }

    /// Segment k with its four control points, phantom points included at the ends.
    /// `k` beyond the last segment gives the last segment, as for clamped u.
    pub fn segment(&self, k: usize) -> Segment {
        let k = k.min(self.centres.len() - 2);
        let c = &self.centres;
        Segment::new([self.before(k), c[k], c[k + 1], self.after(k + 1)])
    }

    /// The control point before centre i: c_{i−1}, or the phantom c₋₁ = 2c₀ − c₁ for i = 0.
    fn before(&self, i: usize) -> DVec3 {
        let c = &self.centres;
        if i == 0 { 2.0 * c[0] - c[1] } else { c[i - 1] }
    }

    /// The control point after centre i: c_{i+1}, or the phantom c_N = 2c_{N−1} − c_{N−2} for
    /// the last centre.
    fn after(&self, i: usize) -> DVec3 {
        let (c, n) = (&self.centres, self.centres.len());
        if i + 1 == n { 2.0 * c[n - 1] - c[n - 2] } else { c[i + 1] }
    }

    /// Fills `out` with every segment's chord deviation bound σ_k, equal bit for bit to
    /// `self.segment(k).chord_deviation_bound()` (`(2/27)(b_k + b_{k+1})` with the bends
    /// b_i = |c_{i−1} − 2c_i + c_{i+1}|, phantom end points as in [`segment`](Self::segment)),
    /// but with each bend computed once and no segment built: the broad phase needs σ of every
    /// segment on every step.
    pub fn chord_deviation_bounds(&self, out: &mut Vec<f64>) {
        let bend = |i: usize| bend(self.before(i), self.centres[i], self.after(i));
        out.clear();
        let mut previous = bend(0);
        for k in 0..self.segment_count() {
            let next = bend(k + 1);
            out.push(chord_deviation_bound(previous, next));
            previous = next;
        }
    }

    /// Point x(u) on the centreline (cm).
    pub fn point(&self, u: f64) -> DVec3 {
        let (k, s) = self.locate(u);
        self.segment(k).point(s)
    }

    /// Tangent x′(u) = dx/du (cm per unit u, ≈ the body length), not normalised.
    pub fn tangent(&self, u: f64) -> DVec3 {
        let (k, s) = self.locate(u);
        self.segment(k).derivative(s)
    }

    /// Second derivative x″(u) = d²x/du² (cm per unit u²).
    pub fn second_derivative(&self, u: f64) -> DVec3 {
        let (k, s) = self.locate(u);
        self.segment(k).second_derivative(s)
    }

    /// Unit tangent t = x′/|x′| pointing toward increasing u (tail-ward), as the
    /// thigmotaxis rows require; zero where x′ = 0 (coincident centres).
    pub fn unit_tangent(&self, u: f64) -> DVec3 {
        self.tangent(u).normalize_or_zero()
    }

    /// Tube radius r(u) = (1 − s) r_k + s r_{k+1} (cm).
    pub fn radius(&self, u: f64) -> f64 {
        let (k, s) = self.locate(u);
        (1.0 - s) * self.radii[k] + s * self.radii[k + 1]
    }

    /// Weights of the real bodies whose blend Σ w_m c_m is x(u), phantom points folded.
    pub fn weights(&self, u: f64) -> SplineWeights {
        let (k, s) = self.locate(u);
        SplineWeights::fold(k, self.body_count(), basis(s))
    }

    /// Weights of the real bodies whose blend Σ w′_m c_m is x′(u), phantom points folded.
    pub fn derivative_weights(&self, u: f64) -> SplineWeights {
        let (k, s) = self.locate(u);
        SplineWeights::fold(k, self.body_count(), basis_derivative(s))
    }

    /// Arc length from the head (u = 0) to u = k + s (cm): the tabulated length up to
    /// u = k plus ∫₀ˢ |x′| ds.
    pub fn arc_length(&self, u: f64) -> f64 {
        let (k, s) = self.locate(u);
        self.cumulative_length()[k] + segment_length(&self.segment(k), s)
    }

    /// Total arc length of the centreline (cm).
    pub fn total_length(&self) -> f64 {
        self.cumulative_length()[self.segment_count()]
    }

    /// Parameter u at arc length `length` from the head (inverse of
    /// [`Centreline::arc_length`]); `length` is clamped to [0, total length].
    pub fn parameter_at_arc_length(&self, length: f64) -> f64 {
        let length = length.clamp(0.0, self.total_length());
        let last = self.segment_count() - 1;
        // First segment whose end lies at or beyond `length`.
        let table = self.cumulative_length();
        let k = table[1..].partition_point(|&end| end < length).min(last);
        let start = table[k];
        let full = table[k + 1] - start;
        k as f64 + invert_segment_length(&self.segment(k), full, length - start)
    }
}

/// Checks the centreline inputs: ≥ 2 finite centres and as many positive, finite radii.
fn validate(centres: &[DVec3], radii: &[f64]) -> Result<(), GeometryError> {
    if centres.len() < 2 {
        return Err(GeometryError::TooFewCentres { count: centres.len() });
    }
    GeometryError::require_length("radii", centres.len(), radii.len())?;
    if let Some((index, &value)) = centres.iter().enumerate().find(|(_, c)| !c.is_finite()) {
        return Err(GeometryError::NonFiniteCentre { index, value });
    }
    if let Some((index, &value)) =
        radii.iter().enumerate().find(|(_, r)| !(r.is_finite() && **r > 0.0))
    {
        return Err(GeometryError::NonPositiveRadius { index, value });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wiggly(n: usize) -> (Vec<DVec3>, Vec<f64>) {
        let centres = (0..n)
            .map(|k| {
                let t = k as f64;
                DVec3::new(0.4 * t, (0.7 * t).sin(), 0.3 * (1.3 * t).cos())
            })
            .collect();
        let radii = (0..n).map(|k| 0.9 - 0.01 * k as f64).collect();
        (centres, radii)
    }

    fn wiggly_centreline(n: usize) -> Centreline {
        let (centres, radii) = wiggly(n);
        Centreline::new(&centres, &radii).expect("valid test centreline")
    }

    /// The arc-length table is built when asked for, and again after every update: a curve
    /// updated to new centres measures what a curve built on them measures.
    #[test]
    fn chord_deviation_bounds_are_those_of_the_segments_bit_for_bit() {
        let line = wiggly_centreline(23);
        let mut bounds = Vec::new();
        line.chord_deviation_bounds(&mut bounds);
        assert_eq!(bounds.len(), line.segment_count());
        for (k, bound) in bounds.iter().enumerate() {
            assert_eq!(bound.to_bits(), line.segment(k).chord_deviation_bound().to_bits(), "{k}");
        }
    }

    #[test]
    fn arc_lengths_follow_every_update() {
        let (centres, radii) = wiggly(12);
        let mut line = Centreline::new(&centres, &radii).expect("valid");
        let before = line.total_length();
        let stretched: Vec<DVec3> = centres.iter().map(|c| *c * 1.5).collect();
        line.update(&stretched, &radii).expect("valid");
        let fresh = Centreline::new(&stretched, &radii).expect("valid");
        assert_eq!(line.total_length(), fresh.total_length());
        assert!((line.total_length() - 1.5 * before).abs() < 1e-9 * before);
        for u in [0.0, 2.5, 7.25, 11.0] {
            assert_eq!(line.arc_length(u), fresh.arc_length(u), "u = {u}");
        }
        assert_eq!(line.parameter_at_arc_length(3.0), fresh.parameter_at_arc_length(3.0));
    }

    #[test]
    fn passes_through_every_centre() {
        let line = wiggly_centreline(12);
        for (k, c) in line.centres().iter().enumerate() {
            assert!(line.point(k as f64).distance(*c) < 1e-14, "x({k}) != c_{k}");
        }
    }

    #[test]
    fn derivatives_match_central_differences_on_every_segment() {
        let line = wiggly_centreline(12);
        let h = 1e-5;
        for k in 0..line.segment_count() {
            for &s in &[0.1, 0.37, 0.5, 0.82, 0.95] {
                let u = k as f64 + s;
                let fd1 = (line.point(u + h) - line.point(u - h)) / (2.0 * h);
                let fd2 = (line.tangent(u + h) - line.tangent(u - h)) / (2.0 * h);
                assert!(line.tangent(u).distance(fd1) < 1e-8, "x' at u = {u}");
                assert!(line.second_derivative(u).distance(fd2) < 1e-8, "x'' at u = {u}");
            }
        }
    }

    #[test]
    fn tangent_is_continuous_across_segment_joints() {
        let line = wiggly_centreline(12);
        for k in 1..line.segment_count() {
            let left = line.segment(k - 1).derivative(1.0);
            let right = line.segment(k).derivative(0.0);
            assert!(left.distance(right) < 1e-14, "x' jumps at u = {k}");
        }
    }

    #[test]
    fn folded_weights_reproduce_points_and_tangents_including_ends() {
        for n in [2, 3, 4, 12] {
            let line = wiggly_centreline(n);
            let steps = 40 * line.segment_count();
            for i in 0..=steps {
                let u = i as f64 / 40.0;
                let w = line.weights(u);
                let dw = line.derivative_weights(u);
                let sum: f64 = w.iter().map(|(_, x)| x).sum();
                let dsum: f64 = dw.iter().map(|(_, x)| x).sum();
                assert!((sum - 1.0).abs() < 1e-14, "weights sum {sum} at u = {u}");
                assert!(dsum.abs() < 1e-13, "derivative weights sum {dsum} at u = {u}");
                let blend = |sw: SplineWeights| {
                    sw.iter().fold(DVec3::ZERO, |acc, (b, x)| acc + x * line.centres()[b])
                };
                assert!(blend(w).distance(line.point(u)) < 1e-13, "x at u = {u}, n = {n}");
                assert!(blend(dw).distance(line.tangent(u)) < 1e-13, "x' at u = {u}, n = {n}");
                assert!(w.len <= 4 && w.bodies[..w.len].is_sorted());
            }
        }
    }

    #[test]
    fn parameter_is_clamped_and_end_maps_to_last_segment() {
        let line = wiggly_centreline(5);
        assert_eq!(line.locate(4.0), (3, 1.0));
        assert_eq!(line.locate(7.5), (3, 1.0));
        assert_eq!(line.locate(-2.0), (0, 0.0));
        assert_eq!(line.locate(2.25), (2, 0.25));
        assert!(line.point(9.0).distance(line.centres()[4]) < 1e-14);
    }

    #[test]
    fn radius_interpolates_linearly_and_tangent_points_tailward() {
        let line = wiggly_centreline(5);
        assert!((line.radius(1.5) - 0.5 * (line.radii()[1] + line.radii()[2])).abs() < 1e-15);
        assert!((line.radius(4.0) - line.radii()[4]).abs() < 1e-15);
        for i in 0..=40 {
            let u = f64::from(i) / 10.0;
            let t = line.unit_tangent(u);
            assert!((t.length() - 1.0).abs() < 1e-14);
            assert!(t.x > 0.0, "the test curve runs along +x, so t must too");
        }
    }

    #[test]
    fn straight_uniform_chain_has_linear_arc_length() {
        let n = 10;
        let centres: Vec<_> = (0..n).map(|k| DVec3::new(0.424 * k as f64, 0.0, 0.0)).collect();
        let line = Centreline::new(&centres, &[0.8; 10]).expect("valid");
        assert!((line.total_length() - 0.424 * 9.0).abs() < 1e-13);
        for i in 0..=90 {
            let u = f64::from(i) / 10.0;
            assert!((line.arc_length(u) - 0.424 * u).abs() < 1e-13, "u = {u}");
        }
    }

    #[test]
    fn arc_length_inverse_round_trips() {
        let line = wiggly_centreline(12);
        for i in 0..=110 {
            let u = f64::from(i) / 10.0;
            let back = line.parameter_at_arc_length(line.arc_length(u));
            assert!((back - u).abs() < 1e-11, "{u} -> {back}");
        }
        assert_eq!(line.parameter_at_arc_length(-1.0), 0.0);
        assert!((line.parameter_at_arc_length(1e9) - 11.0).abs() < 1e-12);
    }

    #[test]
    fn invalid_inputs_are_rejected_with_context() {
        let one = [DVec3::ZERO];
        assert_eq!(
            Centreline::new(&one, &[1.0]).err(),
            Some(GeometryError::TooFewCentres { count: 1 })
        );
        let (mut centres, mut radii) = wiggly(4);
        assert!(matches!(
            Centreline::new(&centres, &radii[..3]),
            Err(GeometryError::LengthMismatch { what: "radii", expected: 4, got: 3 })
        ));
        radii[2] = 0.0;
        assert!(matches!(
            Centreline::new(&centres, &radii),
            Err(GeometryError::NonPositiveRadius { index: 2, .. })
        ));
        radii[2] = 0.5;
        centres[3].y = f64::NAN;
        assert!(matches!(
            Centreline::new(&centres, &radii),
            Err(GeometryError::NonFiniteCentre { index: 3, .. })
        ));
    }

    #[test]
    fn failed_update_keeps_the_previous_curve() {
        let mut line = wiggly_centreline(6);
        let before = line.point(2.5);
        let (mut centres, radii) = wiggly(6);
        centres[0].x = f64::INFINITY;
        assert!(line.update(&centres, &radii).is_err());
        assert_eq!(line.point(2.5), before);
    }
}
