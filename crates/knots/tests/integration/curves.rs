//! Test curves: closed knots from formulas and braid words, cut open with protruding ends,
//! noise, and unknotted open curves.

use std::f64::consts::{PI, TAU};

use glam::DVec3;

use crate::hagfish_curve::{polyline_length, resample, trefoil};

/// `count` samples of the closed curve `curve` over one period t ∈ [0, 2π).
pub fn sample_closed(curve: impl Fn(f64) -> DVec3, count: usize) -> Vec<DVec3> {
    (0..count).map(|k| curve(TAU * k as f64 / count as f64)).collect()
}

/// The closed-form trefoil ([`trefoil`]), 400 samples.
pub fn closed_trefoil() -> Vec<DVec3> {
    sample_closed(trefoil, 400)
}

/// The figure-eight knot ((2 + cos 2t) cos 3t, (2 + cos 2t) sin 3t, sin 4t), 400 samples.
pub fn closed_figure_eight() -> Vec<DVec3> {
    sample_closed(
        |t| {
            let r = 2.0 + (2.0 * t).cos();
            DVec3::new(r * (3.0 * t).cos(), r * (3.0 * t).sin(), (4.0 * t).sin())
        },
        400,
    )
}

/// Parameter of the xy-crossing of [`trefoil`] where the strand at this t passes under the
/// strand at t ≈ 3.91787 (heights ∓0.72618; found numerically).
const SWITCHED_CROSSING: f64 = 0.270_918_132;

/// [`trefoil`] with the crossing at [`SWITCHED_CROSSING`] switched: a narrow bump of height
/// 2 lifts the under-strand above the over-strand there, leaving the xy shadow (hence the
/// other two crossings) unchanged. Switching one crossing of a trefoil diagram unknots it.
pub fn closed_switched_trefoil() -> Vec<DVec3> {
    sample_closed(
        |t| {
            let offset = (t - SWITCHED_CROSSING + PI).rem_euclid(TAU) - PI;
            trefoil(t) + DVec3::Z * 2.0 * (-(offset / 0.12).powi(2)).exp()
        },
        400,
    )
}

/// Closure of a braid: `word` lists generators σᵢ as `i` and σᵢ⁻¹ as `−i` (1-based) on
/// `strands` strands. Strand positions become radii 2·strands + position around the z axis;
/// each generator occupies an equal angular slot in which its two strands swap radii, the
/// one moving outward passing over (z > 0) for σᵢ and under for σᵢ⁻¹. Following one strand
/// through successive turns gives the closed curve, `slot_samples` points per slot; the
/// braid's permutation must be one cycle (a knot, not a link).
pub fn braid_closure(word: &[i32], strands: usize, slot_samples: usize) -> Vec<DVec3> {
    let slots = word.len();
    let mut points = Vec::new();
    let mut position = 0usize;
    for _turn in 0..strands {
        for (slot, &generator) in word.iter().enumerate() {
            let low = generator.unsigned_abs() as usize - 1;
            let moving_out = position == low;
            let next = match position {
                p if p == low => low + 1,
                p if p == low + 1 => low,
                p => p,
            };
            for k in 0..slot_samples {
                let u = k as f64 / slot_samples as f64;
                let x = position as f64
                    + (next as f64 - position as f64) * 0.5 * (1.0 - (PI * u).cos());
                let over = if moving_out == (generator > 0) { 1.0 } else { -1.0 };
                let z = if next == position { 0.0 } else { over * 0.4 * (PI * u).sin() };
                let angle = TAU * (slot as f64 + u) / slots as f64;
                let radius = 2.0 * strands as f64 + x;
                points.push(DVec3::new(radius * angle.cos(), radius * angle.sin(), z));
            }
            position = next;
        }
    }
    assert_eq!(position, 0, "the braid closure is a link, not a knot");
    points
}

/// Deterministic uniform noise in [−1, 1) (SplitMix64).
pub struct Noise(u64);

impl Noise {
    /// A generator with the given seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next sample in [−1, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// A random vector with coordinates in [−1, 1).
    pub fn vector(&mut self) -> DVec3 {
        DVec3::new(self.next(), self.next(), self.next())
    }
}

/// Cuts the closed polyline `closed` open at its point farthest from the centroid: removes
/// the arc within 2 % of the length on either side, resamples the rest to `samples`
/// points, and adds straight tails of half the diameter leaving each cut end outward and
/// away from the other end (10 points each). Then adds noise of ±0.5 % of the diameter per
/// coordinate and multiplies everything by `scale`.
pub fn cut_open(closed: &[DVec3], samples: usize, noise: &mut Noise, scale: f64) -> Vec<DVec3> {
    let n = closed.len();
    let centroid = closed.iter().sum::<DVec3>() / n as f64;
    let diameter = closed.iter().map(|p| p.distance(centroid)).fold(0.0, f64::max) * 2.0;
    let tip = (0..n)
        .max_by(|&i, &j| closed[i].distance(centroid).total_cmp(&closed[j].distance(centroid)))
        .unwrap_or(0);
    // The samples are close to uniform in arc length: 2 % of the length ≈ 2 % of them.
    let gap = (0.02 * n as f64).ceil() as usize;
    let cyclic: Vec<DVec3> = (gap..=n - gap).map(|k| closed[(tip + k) % n]).collect();
    let arc = resample(&cyclic, polyline_length(&cyclic) / (samples - 1) as f64, samples);
    let outward = (closed[tip] - centroid).normalize();
    let (first, last) = (arc[0], arc[arc.len() - 1]);
    let along = (first - last).normalize();
    let tail = |end: DVec3, away: DVec3| {
        let direction = (outward + away).normalize();
        (1..=10).map(move |k| end + 0.05 * diameter * k as f64 * direction)
    };
    let start: Vec<DVec3> = tail(first, along).collect();
    start
        .into_iter()
        .rev()
        .chain(arc)
        .chain(tail(last, -along))
        .map(|p| scale * (p + 0.005 * diameter * noise.vector()))
        .collect()
}
