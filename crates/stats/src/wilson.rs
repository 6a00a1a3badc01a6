//! The Wilson score interval of a success rate, for a yes/no outcome over a grid point's
//! replicates (did the knot tie, did it reach the head).
//!
//! Why Wilson and not the Wald interval p̂ ± z·√(p̂(1 − p̂)/n): Wald collapses to a point at
//! 0/n and n/n and covers far below nominal at small n; Wilson inverts the score test, stays
//! inside [0, 1], and its coverage averaged over p is close to nominal already at n = 8
//! (Brown, Cai & DasGupta, Statist. Sci. 16 (2001) 101). Exact coverage, averaged over p on
//! the grid 0.05, 0.06, …, 0.95 (computed by summing binomial probabilities; the
//! integration test `wilson_exact_coverage`):
//!
//! | n | mean coverage | lowest on the grid |
//! |---|---|---|
//! | 8 | 0.956 | 0.897 |
//! | 30 | 0.951 | 0.930 |
//!
//! (For comparison, by the same sums: the Wald interval 0.793 and 0.916.)

use crate::normal::normal_quantile;

/// The Wilson score interval (low, high) of the success probability from `successes` out of
/// `trials`, at confidence `level` (e.g. 0.95).
///
/// With p̂ = successes/trials, n = trials and z = Φ⁻¹((1 + level)/2):
/// centre = (p̂ + z²/2n)/(1 + z²/n), half-width = z/(1 + z²/n)·√(p̂(1 − p̂)/n + z²/4n²),
/// interval = centre ∓ half-width. Mathematically 0 ≤ low ≤ p̂ ≤ high ≤ 1; the computed ends
/// are clamped to [0, p̂] and [p̂, 1] so that rounding cannot break this, which also makes
/// low exactly 0 at 0 successes and high exactly 1 at n successes.
///
/// Returns `None` when `trials` is 0, `successes` > `trials`, or `level` is not in the open
/// interval (0, 1) (NaN included).
pub fn wilson_interval(successes: usize, trials: usize, level: f64) -> Option<(f64, f64)> {
    if trials == 0 || successes > trials || !(level > 0.0 && level < 1.0) {
        return None;
    }
    let z = normal_quantile((1.0 + level) / 2.0)?;
    let n = trials as f64;
    let p = successes as f64 / n;
    let z2n = z * z / n;
    let centre = (p + z2n / 2.0) / (1.0 + z2n);
    let half = z / (1.0 + z2n) * (p * (1.0 - p) / n + z2n / (4.0 * n)).sqrt();
    Some(((centre - half).clamp(0.0, p), (centre + half).clamp(p, 1.0)))
}

#[cfg(test)]
mod tests {
    use super::wilson_interval;

    #[test]
    fn textbook_values() {
        // 3 of 10 at 95 %: (0.1078, 0.6032) (Newcombe, Stat. Med. 17 (1998) 857, Table II).
        let (low, high) = wilson_interval(3, 10, 0.95).expect("valid");
        assert!((low - 0.1078).abs() < 5e-5 && (high - 0.6032).abs() < 5e-5, "{low} {high}");
        // 0 of 10: low is 0 and high = z²/(n + z²) = 0.2775.
        let (low, high) = wilson_interval(0, 10, 0.95).expect("valid");
        assert_eq!(low, 0.0);
        assert!((high - 0.2775).abs() < 5e-5, "{high}");
        let (low, high) = wilson_interval(10, 10, 0.95).expect("valid");
        assert!((low - 0.7225).abs() < 5e-5, "{low}");
        assert_eq!(high, 1.0);
    }

    #[test]
    fn symmetric_in_successes_and_failures() {
        for k in 0..=12 {
            let (low, high) = wilson_interval(k, 12, 0.9).expect("valid");
            let (low_m, high_m) = wilson_interval(12 - k, 12, 0.9).expect("valid");
            assert!((low - (1.0 - high_m)).abs() < 1e-14 && (high - (1.0 - low_m)).abs() < 1e-14);
        }
    }

    #[test]
    fn invalid_input_is_none() {
        assert_eq!(wilson_interval(0, 0, 0.95), None);
        assert_eq!(wilson_interval(4, 3, 0.95), None);
        for level in [0.0, 1.0, -0.1, 2.0, f64::NAN] {
            assert_eq!(wilson_interval(1, 3, level), None, "level {level}");
        }
    }
}
