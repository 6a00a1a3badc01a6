//! The sample quantile rule of the bootstrap: Hyndman & Fan's type 7 (linear interpolation
//! between order statistics; R's and NumPy's default), stated once so that every interval
//! in the crate uses the same rule.

/// The type-7 quantile of `sorted` (ascending) at probability `p`:
/// with h = (N − 1)·p, Q(p) = x₍⌊h⌋₎ + (h − ⌊h⌋)·(x₍⌊h⌋+1₎ − x₍⌊h⌋₎) on 0-based order
/// statistics, so Q(0) is the minimum and Q(1) the maximum.
///
/// Why type 7: it is continuous in p, needs no tuning and is what R and NumPy report, so a
/// number from here can be checked in either. Returns `None` when `sorted` is empty or `p`
/// is not in [0, 1] (NaN included). The order of `sorted` is the caller's duty (it is not
/// checked). ±∞ entries give no NaN: the lower neighbour is returned as is when the upper
/// one has weight 0, equals it, or the lower one is −∞ (so no ∞ − ∞ is formed); a finite
/// lower and a +∞ upper neighbour give +∞.
pub fn quantile_sorted(sorted: &[f64], p: f64) -> Option<f64> {
    if sorted.is_empty() || !(0.0..=1.0).contains(&p) {
        return None;
    }
    let h = (sorted.len() - 1) as f64 * p;
    let below = h.floor();
    let index = below as usize;
    let weight = h - below;
    let lower = sorted[index];
    match sorted.get(index + 1) {
        Some(&upper) if weight > 0.0 && upper != lower && lower.is_finite() => {
            Some(lower + weight * (upper - lower))
        }
        _ => Some(lower),
    }
}

#[cfg(test)]
mod tests {
    use super::quantile_sorted;

    #[test]
    fn matches_r_type_7() {
        // R: quantile(c(1, 2, 3, 4), c(0, 0.1, 0.5, 0.975, 1), type = 7)
        //    = 1.000 1.300 2.500 3.925 4.000
        let x = [1.0, 2.0, 3.0, 4.0];
        let q = |p| quantile_sorted(&x, p).expect("a quantile");
        assert_eq!(q(0.0), 1.0);
        assert!((q(0.1) - 1.3).abs() < 1e-15);
        assert_eq!(q(0.5), 2.5);
        assert!((q(0.975) - 3.925).abs() < 1e-15);
        assert_eq!(q(1.0), 4.0);
    }

    #[test]
    fn single_value_and_bad_input() {
        assert_eq!(quantile_sorted(&[7.0], 0.3), Some(7.0));
        assert_eq!(quantile_sorted(&[], 0.5), None);
        assert_eq!(quantile_sorted(&[1.0, 2.0], -0.1), None);
        assert_eq!(quantile_sorted(&[1.0, 2.0], 1.1), None);
        assert_eq!(quantile_sorted(&[1.0, 2.0], f64::NAN), None);
    }

    #[test]
    fn infinities_do_not_make_nan() {
        let x = [f64::NEG_INFINITY, f64::NEG_INFINITY, 0.0, f64::INFINITY];
        assert_eq!(quantile_sorted(&x, 0.2), Some(f64::NEG_INFINITY));
        assert_eq!(quantile_sorted(&x, 0.5), Some(f64::NEG_INFINITY));
        assert_eq!(quantile_sorted(&x, 0.9), Some(f64::INFINITY));
        assert_eq!(quantile_sorted(&x, 1.0), Some(f64::INFINITY));
    }
}
