//! Least-squares straight lines with their R², and the unwrapping of angles: the pieces of
//! the travelling-wave fit and of the knot's speed.

use std::f64::consts::PI;

/// The least-squares line y ≈ a + b x through some points, and how well it fits.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct LineFit {
    /// The slope b = Σ(x − x̄)(y − ȳ) / Σ(x − x̄)².
    pub slope: f64,
    /// The intercept a = ȳ − b x̄.
    pub intercept: f64,
    /// R² = 1 − Σ(y − a − b x)² / Σ(y − ȳ)² (1 when y is exactly constant and fitted).
    pub r_squared: f64,
    /// The number of points.
    pub points: usize,
}

/// The least-squares line through `(x, y)`; `None` with fewer than two points or all x equal.
pub fn fit_line(x: &[f64], y: &[f64]) -> Option<LineFit> {
    let n = x.len().min(y.len());
    if n < 2 {
        return None;
    }
    let mean = |v: &[f64]| v[..n].iter().sum::<f64>() / n as f64;
    let (mx, my) = (mean(x), mean(y));
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (xi, yi) in x.iter().zip(y) {
        let (dx, dy) = (xi - mx, yi - my);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    if sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let residual: f64 = x.iter().zip(y).map(|(xi, yi)| (yi - intercept - slope * xi).powi(2)).sum();
    let r_squared = if syy > 0.0 { 1.0 - residual / syy } else { 1.0 };
    Some(LineFit { slope, intercept, r_squared, points: n })
}

/// `angles` (rad) with multiples of 2π added so that no two neighbours differ by more than π.
pub fn unwrap(angles: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(angles.len());
    for &a in angles {
        let next = match out.last() {
            Some(&previous) => a + 2.0 * PI * ((previous - a) / (2.0 * PI)).round(),
            None => a,
        };
        out.push(next);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exact_line_fits_with_r2_one_and_noise_lowers_it() {
        let x = [0.0, 1.0, 2.0, 3.0];
        let fit = fit_line(&x, &[1.0, 3.0, 5.0, 7.0]).expect("a line");
        assert_eq!((fit.slope, fit.intercept, fit.r_squared, fit.points), (2.0, 1.0, 1.0, 4));
        let noisy = fit_line(&x, &[1.0, -1.0, 1.0, -1.0]).expect("a line");
        assert!(noisy.r_squared < 0.5, "{noisy:?}");
        assert!(fit_line(&[1.0, 1.0], &[0.0, 1.0]).is_none());
        assert!(fit_line(&[1.0], &[0.0]).is_none());
    }

    #[test]
    fn unwrapping_removes_the_jumps_of_atan2() {
        let steps: Vec<f64> = (0..20).map(|i| 0.9 * i as f64).collect();
        let wrapped: Vec<f64> = steps.iter().map(|a| a.sin().atan2(a.cos())).collect();
        for (u, s) in unwrap(&wrapped).iter().zip(&steps) {
            assert!((u - s).abs() < 1e-12, "{u} {s}");
        }
    }
}
