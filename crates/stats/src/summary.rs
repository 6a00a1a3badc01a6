//! The summary of one grid point's replicates: n, the mean and the sample standard deviation,
//! computed on the sorted values so that they do not depend on the order in which a sweep's
//! runs finished.

/// n, mean m = Σxᵢ/n and sample standard deviation s = √(Σ(xᵢ − m)²/(n − 1)) of replicates.
///
/// Why: the point estimate and spread that every interval of the crate starts from; s has
/// the n − 1 divisor (unbiased variance), the one a t-statistic (m − μ)/(s/√n) needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Number of replicates.
    pub n: usize,
    /// Sample mean m = Σxᵢ/n.
    pub mean: f64,
    /// Sample standard deviation s = √(Σ(xᵢ − m)²/(n − 1)); exactly 0 when all values are equal.
    pub sd: f64,
}

impl Summary {
    /// The summary of `values` (any order; summed in ascending order, two-pass variance).
    ///
    /// Returns `None` when there are fewer than 2 values (no spread with the n − 1
    /// divisor), when a value is not finite (a diverged run must be filtered by the caller,
    /// not averaged), or when the mean or sd overflows f64. When all values are equal the
    /// mean is that value exactly and sd is exactly 0 (not a rounding residue).
    pub fn of(values: &[f64]) -> Option<Summary> {
        if values.len() < 2 || values.iter().any(|x| !x.is_finite()) {
            return None;
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let (mean, sd) = sorted_moments(&sorted);
        (mean.is_finite() && sd.is_finite()).then_some(Summary { n: values.len(), mean, sd })
    }

    /// The standard error of the mean, s/√n.
    ///
    /// Why: the scale of the t-statistic (m − μ)/(s/√n) that the bootstrap-t studentizes by.
    pub fn standard_error(&self) -> f64 {
        self.sd / (self.n as f64).sqrt()
    }
}

/// (mean, sd) of a non-empty ascending slice: m = Σxᵢ/n summed in slice order, then
/// s = c·√(Σ((xᵢ − m)/c)²/(n − 1)) with c = max|xᵢ|. If the first and last values are equal
/// (all equal) it returns (x₀, 0) exactly; otherwise s > 0 (the scaling c keeps the squares
/// from underflowing), unless x − m overflows, which makes s = ∞.
///
/// Two slices holding the same multiset in ascending order give bit-identical results —
/// the bootstrap relies on this so that a resample that reproduces the data has t* = 0.
pub(crate) fn sorted_moments(sorted: &[f64]) -> (f64, f64) {
    let (first, last) = match (sorted.first(), sorted.last()) {
        (Some(&first), Some(&last)) => (first, last),
        _ => return (f64::NAN, f64::NAN),
    };
    if first == last {
        return (first, 0.0);
    }
    let n = sorted.len() as f64;
    let mean = sorted.iter().sum::<f64>() / n;
    // In units of the largest |x| (at one end, as the slice is sorted): (x − m)² of values
    // near 10⁻²⁰⁰ would underflow to 0 and make unequal values look equal.
    let scale = first.abs().max(last.abs());
    let squares: f64 = sorted.iter().map(|x| ((x - mean) / scale).powi(2)).sum();
    (mean, scale * (squares / (n - 1.0)).sqrt())
}

#[cfg(test)]
mod tests {
    use super::{Summary, sorted_moments};

    #[test]
    fn known_values() {
        // mean 5, Σ(x − m)² = 32, s = √(32/7)
        let s = Summary::of(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]).expect("8 finite values");
        assert_eq!(s.n, 8);
        assert_eq!(s.mean, 5.0);
        assert!((s.sd - (32.0_f64 / 7.0).sqrt()).abs() < 1e-15);
        assert!((s.standard_error() - (32.0_f64 / 7.0 / 8.0).sqrt()).abs() < 1e-15);
    }

    #[test]
    fn order_does_not_matter() {
        let a = [0.1, 0.7, 0.3, 1e-3, 12.5, -4.0];
        let mut b = a;
        b.reverse();
        assert_eq!(Summary::of(&a), Summary::of(&b));
    }

    #[test]
    fn equal_values_are_exact() {
        // 0.1 + 0.1 + 0.1 = 0.30000000000000004: a naive mean would leave a residue.
        let s = Summary::of(&[0.1, 0.1, 0.1]).expect("3 finite values");
        assert_eq!((s.mean, s.sd), (0.1, 0.0));
    }

    #[test]
    fn tiny_values_keep_their_spread() {
        let s = Summary::of(&[1e-200, 2e-200, 3e-200]).expect("3 finite values");
        assert!((s.sd / 1e-200 - 1.0).abs() < 1e-15, "{}", s.sd);
    }

    #[test]
    fn short_or_non_finite_is_none() {
        assert_eq!(Summary::of(&[]), None);
        assert_eq!(Summary::of(&[1.0]), None);
        assert_eq!(Summary::of(&[1.0, f64::NAN]), None);
        assert_eq!(Summary::of(&[1.0, f64::INFINITY]), None);
        assert_eq!(Summary::of(&[f64::MAX, f64::MAX / 2.0]), None);
        assert!(sorted_moments(&[]).0.is_nan());
    }
}
