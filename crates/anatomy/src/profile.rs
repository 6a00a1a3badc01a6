//! The body profile along the arc length: radius r(u) and bending limit θ(u), piecewise
//! linear through the measurement marks and clamped beyond them (D5, D6).

use std::f64::consts::TAU;

use crate::biometrics::Biometrics;

/// Piecewise-linear interpolation through the points `(xs[k], ys[k])`, clamped to `ys[0]`
/// below `xs[0]` and to the last `y` above the last `x`. Between marks
/// `y = (1 − t) y_{k−1} + t y_k` with `t = (x − x_{k−1}) / (x_k − x_{k−1})`, which returns
/// `y_k` exactly at `x = x_k`.
///
/// `xs` must be strictly increasing; extra entries of the longer slice are ignored and empty
/// input gives NaN.
pub fn interpolate_clamped(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let mut points = xs.iter().zip(ys).map(|(&x, &y)| (x, y));
    let Some(mut prev) = points.next() else {
        return f64::NAN;
    };
    if x <= prev.0 {
        return prev.1;
    }
    for (xk, yk) in points {
        if x <= xk {
            let t = (x - prev.0) / (xk - prev.0);
            return (1.0 - t) * prev.1 + t * yk;
        }
        prev = (xk, yk);
    }
    prev.1
}

impl Biometrics {
    /// Body radius (cm) at arc-length fraction `u = s/L`: `r = C(u)/2π` with the
    /// circumference `C` piecewise linear through the marks, clamped before the first mark;
    /// beyond the last mark `u_m` it stays at `r(u_m)`, or with a [`crate::TailTaper`] falls
    /// linearly to the tip radius at `u = 1`.
    pub fn radius_at(&self, u: f64) -> f64 {
        let r = interpolate_clamped(&self.mark_fractions, &self.circumferences_cm, u) / TAU;
        match (self.tail_taper, self.mark_fractions.last()) {
            (Some(taper), Some(&last)) if u > last => {
                let t = ((u - last) / (1.0 - last)).min(1.0);
                (1.0 - t) * r + t * taper.tip_radius_cm
            }
            _ => r,
        }
    }

    /// Symmetric bending limit θ (deg) at arc-length fraction `u = s/L`: piecewise linear
    /// through the marks, clamped beyond the first and last mark (D6).
    pub fn bending_limit_deg_at(&self, u: f64) -> f64 {
        interpolate_clamped(&self.mark_fractions, &self.bending_limits_deg, u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_hits_points_exactly_and_clamps() {
        let xs = [0.2, 0.4, 0.6, 0.8];
        let ys = [5.6, 5.5, 5.6, 4.3];
        for (x, y) in xs.iter().zip(&ys) {
            assert_eq!(interpolate_clamped(&xs, &ys, *x), *y);
        }
        assert_eq!(interpolate_clamped(&xs, &ys, 0.0), 5.6);
        assert_eq!(interpolate_clamped(&xs, &ys, 1.0), 4.3);
        assert!((interpolate_clamped(&xs, &ys, 0.7) - 4.95).abs() < 1e-12);
        assert!((interpolate_clamped(&xs, &ys, 0.25) - 5.575).abs() < 1e-12);
    }

    #[test]
    fn interpolation_of_degenerate_input_does_not_panic() {
        assert!(interpolate_clamped(&[], &[], 0.5).is_nan());
        assert_eq!(interpolate_clamped(&[0.5], &[2.0], 0.1), 2.0);
        assert_eq!(interpolate_clamped(&[0.5], &[2.0], 0.9), 2.0);
        assert_eq!(interpolate_clamped(&[0.2, 0.4], &[1.0], 0.9), 1.0);
    }
}
