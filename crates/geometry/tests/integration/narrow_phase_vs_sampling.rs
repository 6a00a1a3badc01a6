//! The Newton narrow phase against dense sampling plus an independent local refinement.
//!
//! For random pairs of segments, the reference minimum distance is found by a 201 × 201
//! grid over [0, 1]², then coordinate descent with golden-section line searches started
//! from every local minimum of the grid (a method independent of the Newton search).
//! A search that reports `Converged` must match it within 1e-6 cm; searches that report a
//! failure are counted, and the failure rate must stay below 0.1 %. Run with
//! `--nocapture` to see the rates; `HAGFISH_NARROW_PHASE_CASES` sets the number of cases.

use std::cell::Cell;

use glam::DVec3;
use hagfish_geometry::{NewtonStatus, Segment, closest_points};
use proptest::collection::vec;
use proptest::prop_assert;
use proptest::test_runner::{Config, TestCaseError, TestRunner};

const GRID: usize = 200;
const TOLERANCE: f64 = 1e-6;
const BODY_LENGTH: f64 = 0.424;

/// Random cases per test (2000); override with `HAGFISH_NARROW_PHASE_CASES`.
fn cases() -> u32 {
    std::env::var("HAGFISH_NARROW_PHASE_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(2000)
}

/// Golden-section minimisation of `f` on [lo, hi].
fn golden_section(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let ratio = 0.5 * (5.0_f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
    let (mut f1, mut f2) = (f(x1), f(x2));
    while hi - lo > 1e-13 {
        if f1 < f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - ratio * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + ratio * (hi - lo);
            f2 = f(x2);
        }
    }
    0.5 * (lo + hi)
}

/// Coordinate descent on |x_b(t) − x_a(s)| from (s, t), each coordinate by golden section
/// over a window that shrinks as the iterates settle.
fn refine(a: &Segment, b: &Segment, mut s: f64, mut t: f64) -> f64 {
    let distance = |s: f64, t: f64| a.point(s).distance(b.point(t));
    let mut window = 2.0 / GRID as f64;
    for _ in 0..400 {
        let before = distance(s, t);
        s = golden_section(|x| distance(x, t), (s - window).max(0.0), (s + window).min(1.0));
        t = golden_section(|y| distance(s, y), (t - window).max(0.0), (t + window).min(1.0));
        if before - distance(s, t) < 1e-15 {
            window *= 0.5;
            if window < 1e-9 {
                break;
            }
        }
    }
    distance(s, t)
}

/// Reference minimum distance: dense grid, then refinement from each grid local minimum.
fn reference_distance(a: &Segment, b: &Segment) -> f64 {
    let at = |i: usize| i as f64 / GRID as f64;
    let pa: Vec<DVec3> = (0..=GRID).map(|i| a.point(at(i))).collect();
    let pb: Vec<DVec3> = (0..=GRID).map(|j| b.point(at(j))).collect();
    let d = |i: usize, j: usize| pa[i].distance(pb[j]);
    let mut best = f64::INFINITY;
    for i in 0..=GRID {
        for j in 0..=GRID {
            let here = d(i, j);
            let neighbours = (i.saturating_sub(1)..=(i + 1).min(GRID))
                .flat_map(|ni| (j.saturating_sub(1)..=(j + 1).min(GRID)).map(move |nj| (ni, nj)));
            let local_minimum = neighbours.into_iter().all(|(ni, nj)| d(ni, nj) >= here);
            if local_minimum && here < best + 1e-3 {
                best = best.min(refine(a, b, at(i), at(j)));
            }
        }
    }
    best
}

/// Unit vector turned by `angle` from `direction` towards azimuth `azimuth`.
fn turn(direction: DVec3, angle: f64, azimuth: f64) -> DVec3 {
    let (u, v) = direction.any_orthonormal_pair();
    (direction * angle.cos() + (u * azimuth.cos() + v * azimuth.sin()) * angle.sin()).normalize()
}

/// A body-like segment from 14 numbers in [−1, 1]: start near `origin`, steps of
/// 0.424 ± 20 % cm, turns up to the sharpest joint limit (75°) between steps.
fn chain_segment(origin: DVec3, r: &[f64]) -> Segment {
    let start = origin + DVec3::new(r[0], r[1], r[2]) * 0.5;
    let mut direction =
        turn(DVec3::X, r[3].abs() * std::f64::consts::PI, r[4] * std::f64::consts::PI);
    let mut control = [start; 4];
    for step in 0..3 {
        let q = &r[5 + 3 * step..8 + 3 * step];
        control[step + 1] = control[step] + direction * BODY_LENGTH * (1.0 + 0.2 * q[0]);
        direction = turn(direction, q[1].abs() * 75f64.to_radians(), q[2] * std::f64::consts::PI);
    }
    Segment::new(control)
}

/// A segment whose four control points are anywhere in a 1 cm cube around `origin`
/// (loops and cusps included).
fn free_segment(origin: DVec3, r: &[f64]) -> Segment {
    Segment::new(std::array::from_fn(|m| {
        origin + 0.5 * DVec3::new(r[3 * m], r[3 * m + 1], r[3 * m + 2])
    }))
}

/// Counts of one run of random cases.
struct Tally {
    cases: u32,
    /// Searches whose status says they failed.
    flagged: usize,
    /// Converged searches more than `TOLERANCE` away from the sampled minimum.
    missed: usize,
}

/// Runs random segment pairs built by `make` against the sampled minimum. With `strict`, a
/// converged search that misses fails the test at once (and proptest shrinks it);
/// otherwise misses are counted.
fn run(label: &str, strict: bool, make: fn(&[f64]) -> (Segment, Segment)) -> Tally {
    let (flagged, missed, worst) = (Cell::new(0), Cell::new(0), Cell::new(0.0_f64));
    let cases = cases();
    let mut runner =
        TestRunner::new(Config { cases, failure_persistence: None, ..Config::default() });
    let result = runner.run(&vec(-1.0_f64..1.0, 28), |r| {
        let (a, b) = make(&r);
        let found = closest_points(&a, &b);
        prop_assert!((0.0..=1.0).contains(&found.s_a) && (0.0..=1.0).contains(&found.s_b));
        let newton = found.distance_squared.sqrt();
        prop_assert!((a.point(found.s_a).distance(b.point(found.s_b)) - newton).abs() < 1e-12);
        if found.status != NewtonStatus::Converged {
            flagged.set(flagged.get() + 1);
            return Ok(());
        }
        let reference = reference_distance(&a, &b);
        let error = (newton - reference).abs();
        worst.set(worst.get().max(error));
        if error <= TOLERANCE {
            Ok(())
        } else if strict {
            Err(TestCaseError::fail(format!("{found:?}: Newton {newton} vs sampled {reference}")))
        } else {
            missed.set(missed.get() + 1);
            Ok(())
        }
    });
    if let Err(error) = result {
        panic!("{label}: {error}");
    }
    println!(
        "{label}: {cases} cases, {} flagged as failed ({:.3} %), {} converged off the sampled \
         minimum, largest converged error {:.2e} cm",
        flagged.get(),
        100.0 * flagged.get() as f64 / f64::from(cases),
        missed.get(),
        worst.get()
    );
    Tally { cases, flagged: flagged.get(), missed: missed.get() }
}

/// Body-like segments: every converged search must match; failed searches < 0.1 %.
#[test]
fn newton_matches_sampling_on_body_like_segments() {
    let tally = run("body-like segments", true, |r| {
        let offset = DVec3::new(r[0], r[1], r[26]) * 1.5;
        (chain_segment(DVec3::ZERO, &r[..14]), chain_segment(offset, &r[14..28]))
    });
    assert!(tally.flagged as f64 <= 1e-3 * f64::from(tally.cases), "failure rate too high");
}

/// Arbitrary control points (loops and cusps a body with joint limits cannot form):
/// flagged failures plus converged misses must stay below 0.1 %. Measured over 4·10⁵
/// cases: no flagged failure and one miss (by 1.2e-6 cm), so this bound, not zero, keeps
/// the test from flaking.
#[test]
fn newton_matches_sampling_on_arbitrary_nearby_segments() {
    let tally = run("arbitrary segments", false, |r| {
        let offset = DVec3::new(r[24], r[25], r[26]);
        (free_segment(DVec3::ZERO, &r[..12]), free_segment(offset, &r[12..24]))
    });
    let failures = (tally.flagged + tally.missed) as f64;
    assert!(failures <= 1e-3 * f64::from(tally.cases), "failure rate too high");
}
