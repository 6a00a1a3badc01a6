//! What holds for any input: the order of the ends, when the bootstrap interval contains the
//! mean, determinism (same seed → same bits, whatever the order of the values) and the
//! Wilson interval's containment of p̂ inside [0, 1].

use hagfish_stats::{Interval, Summary, mean_interval, wilson_interval};
use proptest::prelude::*;

/// Replicates with ties (small integers) or without (continuous), 3 to 30 of them, over
/// magnitudes from 10⁻⁶ to 10⁶ (cm·s⁻¹ to dyn in the same study).
fn replicates() -> impl Strategy<Value = Vec<f64>> {
    let tied = prop::collection::vec((0_i32..4).prop_map(f64::from), 3..30);
    let spread = (prop::collection::vec(-1.0_f64..1.0, 3..30), -6_i32..7)
        .prop_map(|(v, e)| v.into_iter().map(|x| x * 10_f64.powi(e)).collect());
    prop_oneof![tied, spread]
}

/// Every field as bits, so that −0.0 ≠ 0.0 and NaN = NaN when comparing two results.
fn bits(iv: &Interval) -> [u64; 10] {
    [
        iv.n as u64,
        iv.mean.to_bits(),
        iv.sd.to_bits(),
        iv.level.to_bits(),
        iv.low.to_bits(),
        iv.high.to_bits(),
        iv.t_low.to_bits(),
        iv.t_high.to_bits(),
        iv.used_resamples as u64,
        iv.dropped_resamples as u64,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn bootstrap_invariants(
        values in replicates(),
        level in 0.5_f64..0.999,
        resamples in 1_usize..300,
        seed in any::<u64>(),
    ) {
        let Some(iv) = mean_interval(&values, level, resamples, seed) else {
            // The inputs are valid, so None means every resample was dropped (all its values
            // equal): for these inputs a chance below 10⁻²³ once B ≥ 50.
            prop_assert!(resamples < 50, "None with {resamples} resamples");
            return Ok(());
        };
        let summary = Summary::of(&values).expect("≥ 3 finite values");
        prop_assert_eq!((iv.n, iv.mean, iv.sd), (summary.n, summary.mean, summary.sd));
        prop_assert!(!iv.low.is_nan() && !iv.high.is_nan());
        prop_assert!(iv.low <= iv.high);
        prop_assert!(iv.t_low <= iv.t_high);
        // The mean is inside exactly when the t* quantiles straddle 0 — which is not
        // guaranteed (few resamples, ties), so only the equivalence is asserted.
        let inside = iv.low <= iv.mean && iv.mean <= iv.high;
        prop_assert_eq!(inside, iv.t_low <= 0.0 && 0.0 <= iv.t_high);
        if iv.sd == 0.0 {
            prop_assert_eq!((iv.low, iv.high), (iv.mean, iv.mean));
            prop_assert_eq!((iv.used_resamples, iv.dropped_resamples), (0, 0));
        } else {
            prop_assert_eq!(iv.used_resamples + iv.dropped_resamples, resamples);
            prop_assert!(iv.used_resamples > 0);
        }
        // Deterministic: the same call again, and the values reversed and rotated.
        let again = mean_interval(&values, level, resamples, seed).expect("as before");
        prop_assert_eq!(bits(&again), bits(&iv));
        let mut shuffled = values.clone();
        shuffled.reverse();
        shuffled.rotate_left(values.len() / 3);
        let moved = mean_interval(&shuffled, level, resamples, seed).expect("as before");
        prop_assert_eq!(bits(&moved), bits(&iv));
    }

    #[test]
    fn wilson_invariants(
        (successes, trials) in (1_usize..2000).prop_flat_map(|n| (0..=n, Just(n))),
        level in 0.01_f64..0.9999,
    ) {
        let (low, high) = wilson_interval(successes, trials, level).expect("valid input");
        let p = successes as f64 / trials as f64;
        prop_assert!(0.0 <= low && low <= p && p <= high && high <= 1.0, "{low} {p} {high}");
        // A higher level widens the interval (z grows); 1e-12 for rounding.
        let (low_w, high_w) =
            wilson_interval(successes, trials, (level + 1.0) / 2.0).expect("valid input");
        prop_assert!(low_w <= low + 1e-12 && high - 1e-12 <= high_w);
    }
}
