//! Closest points of two Catmull-Rom segments (thesis Eq. 4.5), by a safeguarded
//! projected Newton method.
//!
//! With Δ = x_b(s_b) − x_a(s_a), the closest points solve
//! F(s_a, s_b) = (x′_a·Δ, x′_b·Δ) = 0 on [0, 1]², whose Jacobian is
//!
//! - ∂F₁/∂s_a = x″_a·Δ − |x′_a|², ∂F₁/∂s_b = x′_a·x′_b,
//! - ∂F₂/∂s_a = −x′_b·x′_a,      ∂F₂/∂s_b = x″_b·Δ + |x′_b|².
//!
//! F = (−g_a, g_b) where g is the gradient of the objective f = ½|Δ|², so the Newton step
//! J δ = −F is the step H δ = −g with the Hessian H of f. Solving through f makes the
//! method a minimisation, which is what keeps it away from the maxima and saddles that
//! plain root finding on F can converge to:
//!
//! 1. search from the chords' closest points and from the few deepest minima of f on a
//!    coarse grid (edges included), keep the closest result, and search once more from a
//!    finer probe next to a segment end if that is closer: so the basin of the global
//!    minimum is searched even when two strands lie side by side (flat f, several
//!    shallow minima);
//! 2. a parameter on a bound whose gradient points out of the box is held fixed and a 1-D
//!    Newton step is taken on the other one;
//! 3. where H is not positive definite (near a saddle), the Gauss–Newton matrix
//!    [[|x′_a|², −x′_a·x′_b], [−x′_a·x′_b, |x′_b|²]] is used, and for parallel tangents its
//!    diagonal;
//! 4. every step is clamped to [0, 1]² and halved until f does not increase (beyond
//!    rounding), so the distance never grows;
//! 5. at most [`MAX_NEWTON_ITERATIONS`] iterations; convergence when every component of
//!    the projected gradient is within [`GRADIENT_TOLERANCE`]. Anything else is reported
//!    in [`ClosestPoints::status`], never hidden.

use glam::DVec3;

use crate::sampled_segment::SampledSegment;
use crate::seeds::{Starts, probe_next_to_bound};
use crate::segment::Segment;

/// Iteration cap of the Newton search (it typically converges in 3–6).
pub const MAX_NEWTON_ITERATIONS: usize = 20;

/// Convergence tolerance on |x′·Δ| (cm², i.e. on each component of F) for parameters not
/// held at a bound.
pub const GRADIENT_TOLERANCE: f64 = 1e-12;

/// Halvings of the step before the line search gives up.
const MAX_STEP_HALVINGS: usize = 40;

/// det(M) ≥ this × M₁₁M₂₂ for a 2×2 matrix to count as positive definite.
const DEFINITENESS_TOLERANCE: f64 = 1e-12;

/// How the closest-point search ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum NewtonStatus {
    /// The projected gradient is within [`GRADIENT_TOLERANCE`]: a local minimum of the
    /// distance on [0, 1]².
    Converged,
    /// [`MAX_NEWTON_ITERATIONS`] were used without converging; the best point found is
    /// reported.
    IterationLimit,
    /// No step along the search direction decreased the distance although the gradient
    /// is above tolerance; the best point found is reported.
    Stalled,
}

/// Closest points between two segments, as local parameters, with the search outcome.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosestPoints {
    /// Local parameter on the first segment, in [0, 1].
    pub s_a: f64,
    /// Local parameter on the second segment, in [0, 1].
    pub s_b: f64,
    /// |x_b(s_b) − x_a(s_a)|² (cm²).
    pub distance_squared: f64,
    /// Newton iterations taken by the search that produced this result.
    pub iterations: usize,
    /// Whether the search converged.
    pub status: NewtonStatus,
}

/// Points, derivatives, Δ, objective and gradient of the search at one (s_a, s_b).
struct Local {
    s: [f64; 2],
    x_a: DVec3,
    x_b: DVec3,
    d_a: DVec3,
    d_b: DVec3,
    dd_a: DVec3,
    dd_b: DVec3,
    delta: DVec3,
    /// ∇(½|Δ|²) = (−x′_a·Δ, x′_b·Δ).
    gradient: [f64; 2],
}

impl Local {
    fn new(a: &Segment, b: &Segment, s: [f64; 2]) -> Local {
        let (x_a, x_b) = (a.point(s[0]), b.point(s[1]));
        let (d_a, d_b) = (a.derivative(s[0]), b.derivative(s[1]));
        let delta = x_b - x_a;
        Local {
            s,
            x_a,
            x_b,
            d_a,
            d_b,
            dd_a: a.second_derivative(s[0]),
            dd_b: b.second_derivative(s[1]),
            delta,
            gradient: [-d_a.dot(delta), d_b.dot(delta)],
        }
    }

    fn distance_squared(&self) -> f64 {
        self.delta.length_squared()
    }

    /// Parameters free to move: not on a bound with the gradient pointing out of the box.
    fn free(&self) -> [bool; 2] {
        // Non-short-circuit `&` and `|`: this runs every iteration, on unpredictable signs.
        [0, 1].map(|i| {
            let g = self.gradient[i];
            !(((self.s[i] <= 0.0) & (g > 0.0)) | ((self.s[i] >= 1.0) & (g < 0.0)))
        })
    }

    /// Largest projected-gradient component (zero for parameters held on a bound).
    fn projected_gradient(&self) -> f64 {
        let free = self.free();
        let component = |i: usize| if free[i] { self.gradient[i].abs() } else { 0.0 };
        0.0_f64.max(component(0)).max(component(1))
    }

    /// Gauss–Newton matrix JᵀJ of Δ(s_a, s_b), J = [−x′_a, x′_b]: positive semi-definite.
    fn gauss_newton(&self) -> [[f64; 2]; 2] {
        let coupling = -self.d_a.dot(self.d_b);
        [[self.d_a.length_squared(), coupling], [coupling, self.d_b.length_squared()]]
    }

    /// Hessian of ½|Δ|²: the Gauss–Newton matrix plus diag(−x″_a·Δ, x″_b·Δ).
    fn hessian(&self) -> [[f64; 2]; 2] {
        let mut hessian = self.gauss_newton();
        hessian[0][0] -= self.dd_a.dot(self.delta);
        hessian[1][1] += self.dd_b.dot(self.delta);
        hessian
    }

    /// Search direction δ on the free parameters (see the module docs, steps 2–3).
    fn step(&self) -> [f64; 2] {
        let g = self.gradient;
        let (hessian, gauss_newton) = (self.hessian(), self.gauss_newton());
        let one_dimensional = |i: usize| {
            let curvature = if hessian[i][i] > 0.0 { hessian[i][i] } else { gauss_newton[i][i] };
            if curvature > 0.0 { -g[i] / curvature } else { 0.0 }
        };
        match self.free() {
            [true, true] => solve_positive_definite(hessian, g)
                .or_else(|| solve_positive_definite(gauss_newton, g))
                .unwrap_or_else(|| [0, 1].map(one_dimensional)),
            [true, false] => [one_dimensional(0), 0.0],
            [false, true] => [0.0, one_dimensional(1)],
            [false, false] => [0.0, 0.0],
        }
    }

    /// Rounding allowance on f = |Δ|²: Δ carries an error of about ε(|x_a| + |x_b|).
    fn rounding_allowance(&self) -> f64 {
        4.0 * f64::EPSILON * self.delta.length() * (self.x_a.length() + self.x_b.length())
    }
}

/// Solves M δ = −g for a symmetric 2×2 M, or `None` if M is not positive definite.
fn solve_positive_definite(m: [[f64; 2]; 2], g: [f64; 2]) -> Option<[f64; 2]> {
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let definite =
        m[0][0] > 0.0 && m[1][1] > 0.0 && det > DEFINITENESS_TOLERANCE * m[0][0] * m[1][1];
    definite.then(|| {
        [-(m[1][1] * g[0] - m[0][1] * g[1]) / det, -(m[0][0] * g[1] - m[1][0] * g[0]) / det]
    })
}

/// Projected Newton search from `start` (steps 2–5 of the module docs).
pub(crate) fn search(a: &Segment, b: &Segment, start: [f64; 2]) -> ClosestPoints {
    let mut local = Local::new(a, b, start);
    let mut iterations = 0;
    let status = loop {
        if local.projected_gradient() <= GRADIENT_TOLERANCE {
            break NewtonStatus::Converged;
        }
        if iterations == MAX_NEWTON_ITERATIONS {
            break NewtonStatus::IterationLimit;
        }
        match line_search(a, b, &local) {
            Some(accepted) => local = accepted,
            None => break NewtonStatus::Stalled,
        }
        iterations += 1;
    };
    ClosestPoints {
        s_a: local.s[0],
        s_b: local.s[1],
        distance_squared: local.distance_squared(),
        iterations,
        status,
    }
}

/// The first point along the search direction from `local`, halving the step from the full
/// one, at which f has not increased beyond rounding (step 4 of the module docs), or `None`
/// after [`MAX_STEP_HALVINGS`] halvings.
fn line_search(a: &Segment, b: &Segment, local: &Local) -> Option<Local> {
    let step = local.step();
    let limit = local.distance_squared() + local.rounding_allowance();
    let mut scale = 1.0;
    for _ in 0..MAX_STEP_HALVINGS {
        let s = [0, 1].map(|i| (local.s[i] + scale * step[i]).clamp(0.0, 1.0));
        scale *= 0.5;
        let trial = Local::new(a, b, s);
        if trial.distance_squared() <= limit && s != local.s {
            return Some(trial);
        }
    }
    None
}

/// Whether search result `found` should replace `best`: converged beats failed, then the
/// smaller distance wins.
fn improves(found: &ClosestPoints, best: &ClosestPoints) -> bool {
    let converged = |c: &ClosestPoints| c.status == NewtonStatus::Converged;
    match (converged(found), converged(best)) {
        (true, false) => true,
        (false, true) => false,
        _ => found.distance_squared < best.distance_squared,
    }
}

/// Closest points of segments `a` and `b` over (s_a, s_b) ∈ [0, 1]² (thesis Eq. 4.5),
/// found by the safeguarded projected Newton method of the module docs: the closest of
/// the converged searches from every start (then from a probe next to a bound, if that
/// is closer), or the closest failed one if none converged.
pub fn closest_points(a: &Segment, b: &Segment) -> ClosestPoints {
    let (a, b) = (SampledSegment::new(*a), SampledSegment::new(*b));
    let starts = Starts::new(&a, &b);
    let first = search(&a.segment, &b.segment, starts.chord());
    search_from_grid(&a.segment, &b.segment, &starts, first)
}

/// [`closest_points`] of `a` and `b` if they may come closer than `reach`, or `None` (no
/// search) when the seed grid already proves every distance ≥ `reach`: the distance at the
/// closest grid point minus half a grid interval times the segments' speed bounds (with a
/// relative allowance of 10⁻⁹ for rounding).
pub fn closest_points_within(a: &Segment, b: &Segment, reach: f64) -> Option<ClosestPoints> {
    let (a, b) = (SampledSegment::new(*a), SampledSegment::new(*b));
    let starts = Starts::new(&a, &b);
    may_come_within(&a, &b, &starts, reach).then(|| {
        let first = search(&a.segment, &b.segment, starts.chord());
        search_from_grid(&a.segment, &b.segment, &starts, first)
    })
}

/// The rest of [`closest_points_within`] once the search from the chords' closest points
/// has returned `first`: `None` if the seed grid proves every distance ≥ `reach`, else the
/// best of `first` and the searches from the grid minima and the edge probe (the same
/// result as [`closest_points_within`], without repeating the first search).
pub(crate) fn closest_points_within_after(
    a: &SampledSegment,
    b: &SampledSegment,
    first: ClosestPoints,
    reach: f64,
) -> Option<ClosestPoints> {
    let starts = Starts::new(a, b);
    may_come_within(a, b, &starts, reach)
        .then(|| search_from_grid(&a.segment, &b.segment, &starts, first))
}

/// Whether the seed grid of `starts` leaves the segments a chance to come closer than
/// `reach` (see [`closest_points_within`]).
fn may_come_within(a: &SampledSegment, b: &SampledSegment, starts: &Starts, reach: f64) -> bool {
    let bound = starts.distance_lower_bound([a.speed_bound, b.speed_bound]);
    bound < reach * (1.0 + ROUNDING_ALLOWANCE)
}

/// Relative allowance for rounding in the pruning bound of [`closest_points_within`].
const ROUNDING_ALLOWANCE: f64 = 1e-9;

/// The searches of [`closest_points`] after the one from the chord start (whose result is
/// `first`): from the grid minima of `starts`, then from the edge probe; the best result.
fn search_from_grid(
    a: &Segment,
    b: &Segment,
    starts: &Starts,
    first: ClosestPoints,
) -> ClosestPoints {
    let keep_better = |best: ClosestPoints, start: [f64; 2]| {
        let found = search(a, b, start);
        if improves(&found, &best) { found } else { best }
    };
    let best = starts.grid_minima().iter().fold(first, |best, &start| keep_better(best, start));
    match probe_next_to_bound(a, b, [best.s_a, best.s_b], best.distance_squared) {
        Some(start) => keep_better(best, start),
        None => best,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight, uniformly parameterised segment from `from` to `to`.
    fn straight(from: DVec3, to: DVec3) -> Segment {
        let d = to - from;
        Segment::new([from - d, from, to, to + d])
    }

    fn assert_converged(found: &ClosestPoints, s_a: f64, s_b: f64, distance: f64) {
        assert_eq!(found.status, NewtonStatus::Converged, "{found:?}");
        assert!((found.s_a - s_a).abs() < 1e-9 && (found.s_b - s_b).abs() < 1e-9, "{found:?}");
        assert!((found.distance_squared.sqrt() - distance).abs() < 1e-12, "{found:?}");
    }

    #[test]
    fn crossing_segments_meet_in_their_middles() {
        let a = straight(DVec3::new(-1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0));
        let b = straight(DVec3::new(0.0, -1.0, 0.7), DVec3::new(0.0, 1.0, 0.7));
        assert_converged(&closest_points(&a, &b), 0.5, 0.5, 0.7);
        let touching = straight(DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.0, 1.0, 0.0));
        assert_converged(&closest_points(&a, &touching), 0.5, 0.5, 0.0);
    }

    #[test]
    fn separated_segments_meet_at_their_ends() {
        let a = straight(DVec3::ZERO, DVec3::X);
        let b = straight(DVec3::new(2.0, 1.0, 0.0), DVec3::new(3.0, 3.0, 0.0));
        assert_converged(&closest_points(&a, &b), 1.0, 0.0, 2f64.sqrt());
    }

    #[test]
    fn parallel_segments_converge_to_some_closest_pair() {
        let a = straight(DVec3::ZERO, DVec3::X);
        let b = straight(DVec3::new(0.5, 0.8, 0.0), DVec3::new(1.5, 0.8, 0.0));
        let found = closest_points(&a, &b);
        assert_eq!(found.status, NewtonStatus::Converged);
        assert!((found.distance_squared.sqrt() - 0.8).abs() < 1e-12);
        assert!((a.point(found.s_a).x - b.point(found.s_b).x).abs() < 1e-9);
    }

    #[test]
    fn point_like_segment_gives_point_to_curve_distance() {
        let a = Segment::new([DVec3::new(0.5, 0.0, 1.0); 4]);
        let b = straight(DVec3::ZERO, DVec3::X);
        let found = closest_points(&a, &b);
        assert_eq!(found.status, NewtonStatus::Converged);
        assert!((found.s_b - 0.5).abs() < 1e-9 && (found.distance_squared - 1.0).abs() < 1e-12);
    }

    #[test]
    fn hessian_and_gradient_match_finite_differences() {
        let a = Segment::new([
            DVec3::new(-0.4, 0.1, 0.0),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.4, 0.2, -0.1),
            DVec3::new(0.7, 0.5, 0.1),
        ]);
        let b = Segment::new([
            DVec3::new(0.3, -0.5, 0.6),
            DVec3::new(0.2, -0.1, 0.5),
            DVec3::new(0.25, 0.3, 0.45),
            DVec3::new(0.4, 0.6, 0.3),
        ]);
        let (s, h) = ([0.3, 0.6], 1e-6);
        let local = Local::new(&a, &b, s);
        let half_f = |s: [f64; 2]| 0.5 * Local::new(&a, &b, s).distance_squared();
        let shifted = |i: usize, by: f64| {
            let mut t = s;
            t[i] += by;
            t
        };
        for i in 0..2 {
            let fd = (half_f(shifted(i, h)) - half_f(shifted(i, -h))) / (2.0 * h);
            assert!((local.gradient[i] - fd).abs() < 1e-9, "gradient {i}");
            let g_plus = Local::new(&a, &b, shifted(i, h)).gradient;
            let g_minus = Local::new(&a, &b, shifted(i, -h)).gradient;
            for j in 0..2 {
                let fd = (g_plus[j] - g_minus[j]) / (2.0 * h);
                assert!((local.hessian()[j][i] - fd).abs() < 1e-8, "hessian {j}{i}");
            }
        }
        // The thesis' Jacobian of F = (x′_a·Δ, x′_b·Δ) = (−g_a, g_b) is diag(−1, 1)·H.
        let (d_a, d_b, dd_a, dd_b, delta) =
            (local.d_a, local.d_b, local.dd_a, local.dd_b, local.delta);
        let thesis = [
            [dd_a.dot(delta) - d_a.length_squared(), d_a.dot(d_b)],
            [-d_b.dot(d_a), dd_b.dot(delta) + d_b.length_squared()],
        ];
        let hessian = local.hessian();
        for j in 0..2 {
            assert!((thesis[0][j] + hessian[0][j]).abs() < 1e-15);
            assert!((thesis[1][j] - hessian[1][j]).abs() < 1e-15);
        }
    }

    #[test]
    fn pruning_never_drops_a_pair_within_reach_and_drops_far_ones() {
        let bent = |origin: DVec3, turn: f64| {
            let p = [0.0, 1.0, 2.0, 3.0].map(|i: f64| {
                let angle = turn * i;
                origin + 0.424 * DVec3::new(i, angle.sin() * i, (0.7 * angle).cos() - 1.0)
            });
            Segment::new(p)
        };
        let mut pruned = 0;
        for i in 0..400 {
            let x = f64::from(i);
            let a = bent(DVec3::ZERO, 0.3 * (0.37 * x).sin());
            let offset =
                DVec3::new((0.91 * x).sin(), (1.3 * x).cos(), 0.5 + 0.6 * (0.17 * x).sin());
            let b = bent(offset, 0.4 * (0.53 * x).cos());
            let found = closest_points(&a, &b);
            let distance = found.distance_squared.sqrt();
            let within = closest_points_within(&a, &b, distance + 1e-9);
            assert_eq!(within, Some(found), "pair {i} within reach was pruned");
            if closest_points_within(&a, &b, 0.5 * distance).is_none() {
                pruned += 1;
            }
        }
        assert!(pruned > 200, "only {pruned} of 400 pairs pruned at half their distance");
    }

    #[test]
    fn result_is_reported_with_the_closest_of_several_minima() {
        // Segment b bulges away from a (z ≈ 0.62 in its middle), so the distance has two
        // local minima at the ends of b (z = 0.6 and z = 0.5); the deeper one must win.
        let a = straight(DVec3::new(-1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0));
        let b = Segment::new([
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(-0.5, 0.0, 0.6),
            DVec3::new(0.5, 0.0, 0.5),
            DVec3::new(1.0, 0.0, 0.0),
        ]);
        let found = closest_points(&a, &b);
        let sampled = (0..=1000)
            .flat_map(|i| (0..=1000).map(move |j| (f64::from(i) / 1e3, f64::from(j) / 1e3)))
            .map(|(s, t)| a.point(s).distance(b.point(t)))
            .fold(f64::INFINITY, f64::min);
        assert_eq!(found.status, NewtonStatus::Converged);
        assert!(
            (found.s_b - 1.0).abs() < 1e-12 && (found.distance_squared.sqrt() - 0.5).abs() < 1e-12
        );
        assert!(found.distance_squared.sqrt() <= sampled + 1e-12);
    }
}
