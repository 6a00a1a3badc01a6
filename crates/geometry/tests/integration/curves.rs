//! Tangled centrelines of 100 hagfish-sized bodies, shared by the contact tests and the
//! benchmark (included with `#[path]`).

use glam::DVec3;

/// Body length ℓ = L/N = 42.4 cm / 100 (cm).
pub const BODY_LENGTH: f64 = 0.424;

/// Number of bodies.
pub const BODY_COUNT: usize = 100;

/// Radii from the circumferences at 20/40/60/80 % of the length (docs/physics.md, "Body"),
/// piecewise linear in arc length and clamped at the ends.
pub fn hagfish_radii(n: usize) -> Vec<f64> {
    let marks = [(0.2, 0.891), (0.4, 0.875), (0.6, 0.891), (0.8, 0.684)];
    (0..n)
        .map(|k| {
            let x = (k as f64 + 0.5) / n as f64;
            match marks.iter().position(|&(at, _)| at > x) {
                Some(0) => marks[0].1,
                None => marks[3].1,
                Some(i) => {
                    let ((x0, r0), (x1, r1)) = (marks[i - 1], marks[i]);
                    r0 + (r1 - r0) * (x - x0) / (x1 - x0)
                }
            }
        })
        .collect()
}

/// A helix of radius 1.6 cm and pitch 1.5 cm (< 2r, so neighbouring turns press on each
/// other along lines), with consecutive centres one body length apart along the curve.
pub fn helix(n: usize) -> Vec<DVec3> {
    let (radius, pitch) = (1.6, 1.5);
    let rise = pitch / std::f64::consts::TAU;
    let step = BODY_LENGTH / (radius * radius + rise * rise).sqrt();
    (0..n)
        .map(|k| {
            let angle = k as f64 * step;
            DVec3::new(rise * angle, radius * angle.cos(), radius * angle.sin())
        })
        .collect()
}

/// A smooth random walk with steps of one body length, turning at most ~35° per step and
/// pulled toward the origin, so that it crosses itself many times within a few cm.
pub fn tangle(n: usize, seed: u64) -> Vec<DVec3> {
    let mut state = seed;
    let mut uniform = move || {
        // SplitMix64, mapped to [−1, 1).
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    let mut point = DVec3::ZERO;
    let mut direction = DVec3::X;
    let mut centres = Vec::with_capacity(n);
    for _ in 0..n {
        centres.push(point);
        let kick = DVec3::new(uniform(), uniform(), uniform()) * 0.35;
        let pull = -0.08 * point;
        direction = (direction + kick + pull.clamp_length_max(0.3)).normalize();
        point += BODY_LENGTH * direction;
    }
    centres
}
