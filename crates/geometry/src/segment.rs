//! One segment of the uniform Catmull-Rom spline and its basis functions.
//!
//! Segment k of the centreline joins c_k (s = 0) and c_{k+1} (s = 1) and is the blend
//! x(s) = Σ_m w_m(s) P_m of its four control points P = (c_{k−1}, c_k, c_{k+1}, c_{k+2}),
//! with the uniform Catmull-Rom weights
//!
//! - w₀ = ½(−s + 2s² − s³)
//! - w₁ = ½(2 − 5s² + 3s³)
//! - w₂ = ½(s + 4s² − 3s³)
//! - w₃ = ½(−s² + s³)
//!
//! The first and second derivatives in s use the derivatives of these cubics. Because the
//! global parameter is u = k + s, d/du = d/ds. The weights themselves are needed for the
//! solver's contact Jacobians ([`crate::SplineWeights`]); positions are evaluated in the
//! equivalent power basis.

use glam::DVec3;

/// Catmull-Rom weights w₀..w₃ at local parameter `s` (they sum to 1).
pub(crate) fn basis(s: f64) -> [f64; 4] {
    let s2 = s * s;
    let s3 = s2 * s;
    [
        0.5 * (-s + 2.0 * s2 - s3),
        0.5 * (2.0 - 5.0 * s2 + 3.0 * s3),
        0.5 * (s + 4.0 * s2 - 3.0 * s3),
        0.5 * (-s2 + s3),
    ]
}

/// First derivatives dw_m/ds of the Catmull-Rom weights (they sum to 0):
/// ½(−1 + 4s − 3s²), ½(−10s + 9s²), ½(1 + 8s − 9s²), ½(−2s + 3s²).
pub(crate) fn basis_derivative(s: f64) -> [f64; 4] {
    let s2 = s * s;
    [
        0.5 * (-1.0 + 4.0 * s - 3.0 * s2),
        0.5 * (-10.0 * s + 9.0 * s2),
        0.5 * (1.0 + 8.0 * s - 9.0 * s2),
        0.5 * (-2.0 * s + 3.0 * s2),
    ]
}

/// One cubic piece of the centreline, built from its four control points.
///
/// It is the unit the narrow phase works on: closest points are searched between two
/// segments, each parameterised by s ∈ [0, 1]. The end segments of a centreline carry the
/// phantom points c₋₁ = 2c₀ − c₁ and c_N = 2c_{N−1} − c_{N−2} as control points, so a
/// `Segment` never needs to know where it sits in the chain.
///
/// The weights above are expanded once into the power basis
/// x(s) = A + Bs + Cs² + Ds³ with A = P₁, B = ½(P₂ − P₀), C = ½(2P₀ − 5P₁ + 4P₂ − P₃),
/// D = ½(−P₀ + 3P₁ − 3P₂ + P₃), so that each evaluation is a Horner scheme (the Newton
/// search evaluates segments many times).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    control: [DVec3; 4],
    /// Power-basis coefficients (A, B, C, D).
    coefficients: [DVec3; 4],
}

impl Segment {
    /// The segment with control points (c_{k−1}, c_k, c_{k+1}, c_{k+2}); it runs from
    /// `control[1]` (s = 0) to `control[2]` (s = 1).
    pub fn new(control: [DVec3; 4]) -> Segment {
        let [p0, p1, p2, p3] = control;
        Segment {
            control,
            coefficients: [
                p1,
                0.5 * (p2 - p0),
                0.5 * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3),
                0.5 * (-p0 + 3.0 * (p1 - p2) + p3),
            ],
        }
    }

    /// The control points (c_{k−1}, c_k, c_{k+1}, c_{k+2}).
    pub fn control(&self) -> &[DVec3; 4] {
        &self.control
    }

    /// Point x(s) = A + s(B + s(C + sD)) = Σ w_m(s) P_m on the segment.
    pub fn point(&self, s: f64) -> DVec3 {
        let [a, b, c, d] = self.coefficients;
        a + s * (b + s * (c + s * d))
    }

    /// First derivative x′(s) = B + s(2C + 3sD) (equal to dx/du on the centreline).
    pub fn derivative(&self, s: f64) -> DVec3 {
        let [_, b, c, d] = self.coefficients;
        b + s * (2.0 * c + 3.0 * s * d)
    }

    /// Second derivative x″(s) = 2C + 6sD (equal to d²x/du² on the centreline).
    pub fn second_derivative(&self, s: f64) -> DVec3 {
        let [_, _, c, d] = self.coefficients;
        2.0 * c + 6.0 * s * d
    }

    /// Upper bound on the speed |x′(s)| over s ∈ [0, 1]: x′ is the quadratic Bézier curve
    /// with control vectors B, B + C and B + 2C + 3D, which lies in their convex hull.
    pub fn speed_bound(&self) -> f64 {
        let [_, b, c, d] = self.coefficients;
        b.length().max((b + c).length()).max((b + 2.0 * c + 3.0 * d).length())
    }

    /// The chord from x(0) = `control[1]` to x(1) = `control[2]`, the straight-line
    /// approximation used to start the narrow phase.
    pub fn chord(&self) -> (DVec3, DVec3) {
        (self.control[1], self.control[2])
    }

    /// Upper bound on the distance between the segment and its chord at equal s:
    /// |x(s) − ((1 − s)P₁ + sP₂)| ≤ (2/27)(|P₀ − 2P₁ + P₂| + |P₁ − 2P₂ + P₃|).
    ///
    /// Catmull-Rom reproduces straight lines, so the deviation is w₀(s)(P₀ − 2P₁ + P₂) +
    /// w₃(s)(P₁ − 2P₂ + P₃), and |w₀|, |w₃| ≤ 2/27 on [0, 1]. It lets the detector skip
    /// segment pairs whose chords are too far apart to touch, without a search.
    pub fn chord_deviation_bound(&self) -> f64 {
        let [p0, p1, p2, p3] = self.control;
        chord_deviation_bound(bend(p0, p1, p2), bend(p1, p2, p3))
    }
}

/// The bend `|P₀ − 2P₁ + P₂|` of three consecutive control points (a second difference).
pub(crate) fn bend(p0: DVec3, p1: DVec3, p2: DVec3) -> f64 {
    (p0 - 2.0 * p1 + p2).length()
}

/// [`Segment::chord_deviation_bound`] from the bends at the segment's two ends:
/// `(2/27)(b₁ + b₂)`.
pub(crate) fn chord_deviation_bound(bend_start: f64, bend_end: f64) -> f64 {
    (2.0 / 27.0) * (bend_start + bend_end)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_segment() -> Segment {
        Segment::new([
            DVec3::new(-0.4, 0.1, 0.0),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.4, 0.2, -0.1),
            DVec3::new(0.7, 0.5, 0.1),
        ])
    }

    /// Σ_m w_m P_m with the given weights.
    fn blend(seg: &Segment, weights: [f64; 4]) -> DVec3 {
        seg.control().iter().zip(weights).map(|(p, w)| w * *p).sum()
    }

    #[test]
    fn power_basis_equals_catmull_rom_blend() {
        let seg = sample_segment();
        for i in 0..=20 {
            let s = f64::from(i) / 20.0;
            assert!(seg.point(s).distance(blend(&seg, basis(s))) < 1e-15);
            assert!(seg.derivative(s).distance(blend(&seg, basis_derivative(s))) < 1e-14);
        }
    }

    #[test]
    fn basis_sums_to_one_and_derivative_sums_to_zero() {
        for i in 0..=20 {
            let s = f64::from(i) / 20.0;
            assert!((basis(s).iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(basis_derivative(s).iter().sum::<f64>().abs() < 1e-14);
        }
    }

    #[test]
    fn segment_interpolates_its_inner_control_points() {
        let seg = sample_segment();
        let p = seg.control();
        assert!(seg.point(0.0).distance(p[1]) < 1e-15);
        assert!(seg.point(1.0).distance(p[2]) < 1e-15);
        // Catmull-Rom tangents at the ends are central differences of the control points.
        let t0 = 0.5 * (p[2] - p[0]);
        let t1 = 0.5 * (p[3] - p[1]);
        assert!(seg.derivative(0.0).distance(t0) < 1e-15);
        assert!(seg.derivative(1.0).distance(t1) < 1e-15);
    }

    #[test]
    fn chord_deviation_bound_holds_and_is_zero_for_straight_uniform_points() {
        let seg = sample_segment();
        let (p1, p2) = seg.chord();
        let bound = seg.chord_deviation_bound();
        let worst = (0..=1000)
            .map(|i| {
                let s = f64::from(i) / 1000.0;
                seg.point(s).distance((1.0 - s) * p1 + s * p2)
            })
            .fold(0.0, f64::max);
        assert!(worst <= bound && worst > 0.3 * bound, "{worst} vs {bound}");
        let straight = Segment::new([0.0, 1.0, 2.0, 3.0].map(|x| DVec3::new(x, 0.5, 0.0)));
        assert_eq!(straight.chord_deviation_bound(), 0.0);
    }

    #[test]
    fn speed_bound_holds_and_is_tight_for_a_straight_segment() {
        let seg = sample_segment();
        let bound = seg.speed_bound();
        let speeds = (0..=1000).map(|i| seg.derivative(f64::from(i) / 1000.0).length());
        let worst = speeds.fold(0.0, f64::max);
        assert!(worst <= bound && worst > 0.5 * bound, "{worst} vs {bound}");
        let straight = Segment::new([0.0, 1.0, 2.0, 3.0].map(|x| DVec3::new(x, 0.5, 0.0)));
        assert!((straight.speed_bound() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn derivatives_match_central_differences() {
        let seg = sample_segment();
        let h = 1e-5;
        for i in 1..10 {
            let s = f64::from(i) / 10.0;
            let fd1 = (seg.point(s + h) - seg.point(s - h)) / (2.0 * h);
            let fd2 = (seg.derivative(s + h) - seg.derivative(s - h)) / (2.0 * h);
            assert!(seg.derivative(s).distance(fd1) < 1e-9, "x' at s = {s}");
            assert!(seg.second_derivative(s).distance(fd2) < 1e-9, "x'' at s = {s}");
        }
    }
}
