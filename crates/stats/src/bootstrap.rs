//! The studentized bootstrap (bootstrap-t) confidence interval of a mean, for a grid point
//! whose N = 3…30 replicated runs scatter because the dynamics are chaotic.
//!
//! From the data x₁…xₙ with mean m and sample sd s (n − 1 divisor), draw B resamples of n
//! values with replacement; for each, t*_b = (m*_b − m)/(s*_b/√n). With the type-7 quantiles
//! t*_(α) of the t*'s (see [`quantile_sorted`]) the interval at level 1 − α is
//!
//! > [m − t*_((1+level)/2)·s/√n,  m − t*_((1−level)/2)·s/√n]
//!
//! — the upper quantile makes the lower end: the bootstrap learns how far the sample mean
//! falls *above* the truth, and that is subtracted.
//!
//! Why bootstrap-t and not the percentile interval (the quantiles of m* themselves): the
//! percentile interval is about m ± z·σ̂/√n with the plug-in σ̂ = s·√((n − 1)/n) and normal
//! quantiles, too short at small n — at n = 8 it covers a normal mean only ≈ 89 % of the time
//! at nominal 95 %. Studentizing corrects both the scale and, being second-order accurate,
//! the skew of the mean's distribution.
//!
//! Measured coverage of the true mean at nominal 95 %, 20 000 seeded studies per row
//! (binomial standard error ±0.0015; normal: mean 10, sd 2; exponential: mean 1, skewness 2;
//! `cargo run -p hagfish-stats --release --example coverage_table`):
//!
//! | data | n | bootstrap-t, B = 999 | bootstrap-t, B = 399 | percentile, B = 999 |
//! |---|---|---|---|---|
//! | normal | 3 | 0.813 | 0.813 | 0.752 |
//! | normal | 5 | 0.944 | 0.942 | 0.831 |
//! | normal | 8 | 0.949 | 0.947 | 0.885 |
//! | normal | 15 | 0.946 | 0.944 | 0.917 |
//! | normal | 30 | 0.946 | 0.943 | 0.931 |
//! | exponential | 3 | 0.788 | 0.788 | 0.696 |
//! | exponential | 5 | 0.927 | 0.925 | 0.782 |
//! | exponential | 8 | 0.935 | 0.933 | 0.839 |
//! | exponential | 15 | 0.942 | 0.939 | 0.888 |
//! | exponential | 30 | 0.944 | 0.940 | 0.913 |
//!
//! From n = 5 the bootstrap-t is within 0.025 of nominal even for skewed data, where the
//! percentile interval misses by 0.02 (n = 30) to 0.17. At n = 3 no bootstrap is good (0.81, 0.79):
//! the resamples of 3 values take only 7 distinct t*'s, too coarse for the tails of a
//! t-statistic with 2 degrees of freedom; read an n = 3 interval as a rough one.
//!
//! Degenerate resamples — all n drawn values equal, so s* = 0 and t* is undefined — are
//! dropped and counted in [`Interval::dropped_resamples`]; at n = 3 that is 1/9 of them, at
//! n = 8 about 1 in 2·10⁶. The data are sorted before resampling and each resample is
//! summed in ascending order, so the interval does not depend on the order of `values`, and
//! a resample that reproduces the data's multiset has t* = 0 exactly.
//!
//! The interval need not contain m: it does exactly when t*_((1−level)/2) ≤ 0 ≤
//! t*_((1+level)/2) (the fields [`Interval::t_low`] and [`Interval::t_high`]). That holds
//! for ordinary data and B in the hundreds or more, but fails for a handful of resamples, and
//! with ties m can be an end point: for [0, 0, 0, 0, 0, 0, 0, 100] every kept resample has
//! m* ≥ m, so the interval is [m − t*·s/√n, m].

use crate::draw::IndexDraw;
use crate::quantile::quantile_sorted;
use crate::summary::sorted_moments;

/// A confidence interval of a mean with the numbers it was made from.
///
/// Why the extra fields: `t_low`/`t_high` show how skewed the replicates are (a symmetric
/// case has t_low ≈ −t_high) and whether the interval contains the mean; the resample counts
/// say how much of the requested bootstrap was usable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// Number of values.
    pub n: usize,
    /// Sample mean m = Σxᵢ/n.
    pub mean: f64,
    /// Sample standard deviation s = √(Σ(xᵢ − m)²/(n − 1)).
    pub sd: f64,
    /// Confidence level, e.g. 0.95.
    pub level: f64,
    /// Lower end, m − t_high·s/√n.
    pub low: f64,
    /// Upper end, m − t_low·s/√n.
    pub high: f64,
    /// The (1 − level)/2 quantile of the bootstrap t*'s (0 when all values are equal).
    pub t_low: f64,
    /// The (1 + level)/2 quantile of the bootstrap t*'s (0 when all values are equal).
    pub t_high: f64,
    /// Resamples whose t* entered the quantiles (0 when all values are equal).
    pub used_resamples: usize,
    /// Resamples dropped because all their values were equal (s* = 0, t* undefined).
    pub dropped_resamples: usize,
}

/// The bootstrap-t confidence interval of the mean of `values` at `level` (e.g. 0.95), from
/// `resamples` resamples drawn from ChaCha8 seeded with `seed` (same input and seed → the
/// same result bit for bit, whatever the order of `values`, on any platform).
///
/// t*_b = (m*_b − m)/(s*_b/√n); interval [m − t*_((1+level)/2)·s/√n, m − t*_((1−level)/2)·s/√n]
/// with type-7 quantiles. B = 999 or more is the usual choice for a 95 % interval.
///
/// When all values are equal (s = 0) the result is the degenerate interval [m, m] with no
/// resampling (`used_resamples` = `dropped_resamples` = 0, `t_low` = `t_high` = 0).
///
/// Returns `None` when:
/// - `level` is not in the open interval (0, 1), or `resamples` is 0;
/// - there are fewer than 3 or more than 2³² values — at n = 2 every kept resample is the
///   data itself, all t* are 0 and the interval would be the zero-width [m, m]; n = 3 is the
///   least that can say anything (and says it roughly: see the module doc's table);
/// - a value is not finite (filter diverged runs first), or m, s or a t* overflows f64;
/// - every resample was dropped (possible only for a tiny `resamples`).
pub fn mean_interval(values: &[f64], level: f64, resamples: usize, seed: u64) -> Option<Interval> {
    let n = values.len();
    let level_ok = level > 0.0 && level < 1.0;
    if !level_ok || resamples == 0 || n < 3 || values.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (mean, sd) = sorted_moments(&sorted);
    if !(mean.is_finite() && sd.is_finite()) {
        return None;
    }
    let degenerate = Interval {
        n,
        mean,
        sd,
        level,
        low: mean,
        high: mean,
        t_low: 0.0,
        t_high: 0.0,
        used_resamples: 0,
        dropped_resamples: 0,
    };
    if sd == 0.0 {
        return Some(degenerate);
    }
    let root_n = (n as f64).sqrt();
    let mut draw = IndexDraw::new(n, seed)?;
    let mut counts = vec![0_usize; n];
    let mut resample = vec![0.0; n];
    let mut t = Vec::with_capacity(resamples.min(1 << 16));
    for _ in 0..resamples {
        counts.fill(0);
        for _ in 0..n {
            counts[draw.next_index()] += 1;
        }
        // Ascending, because `sorted` is and each value is repeated in place.
        let mut filled = 0;
        for (&x, &k) in sorted.iter().zip(&counts) {
            resample[filled..filled + k].fill(x);
            filled += k;
        }
        let (m, s) = sorted_moments(&resample);
        if s == 0.0 {
            continue;
        }
        let t_b = (m - mean) * root_n / s;
        if !t_b.is_finite() {
            return None;
        }
        t.push(t_b);
    }
    t.sort_by(f64::total_cmp);
    let t_low = quantile_sorted(&t, (1.0 - level) / 2.0)?;
    let t_high = quantile_sorted(&t, (1.0 + level) / 2.0)?;
    let se = sd / root_n;
    Some(Interval {
        low: mean - t_high * se,
        high: mean - t_low * se,
        t_low,
        t_high,
        used_resamples: t.len(),
        dropped_resamples: resamples - t.len(),
        ..degenerate
    })
}

#[cfg(test)]
mod tests {
    use super::mean_interval;

    const DATA: [f64; 8] = [3.1, 2.7, 3.9, 2.2, 3.3, 5.8, 2.9, 3.0];

    #[test]
    fn summary_fields_and_order_of_ends() {
        let iv = mean_interval(&DATA, 0.95, 999, 7).expect("8 finite values");
        assert_eq!(iv.n, 8);
        assert!((iv.mean - 26.9 / 8.0).abs() < 1e-12);
        assert!(iv.low < iv.mean && iv.mean < iv.high);
        assert!(iv.t_low < 0.0 && 0.0 < iv.t_high);
        assert_eq!(iv.used_resamples + iv.dropped_resamples, 999);
        // One high outlier (5.8): the mean's distribution is right-skewed, so bootstrap-t
        // reaches further above m than below it.
        assert!(iv.high - iv.mean > iv.mean - iv.low);
    }

    #[test]
    fn a_wider_level_gives_a_wider_interval() {
        let narrow = mean_interval(&DATA, 0.8, 999, 7).expect("8 finite values");
        let wide = mean_interval(&DATA, 0.99, 999, 7).expect("8 finite values");
        assert!(wide.low < narrow.low && narrow.high < wide.high);
    }

    #[test]
    fn equal_values_give_the_point() {
        let iv = mean_interval(&[0.1; 5], 0.95, 999, 1).expect("5 finite values");
        assert_eq!((iv.low, iv.mean, iv.high, iv.sd), (0.1, 0.1, 0.1, 0.0));
        assert_eq!((iv.used_resamples, iv.dropped_resamples), (0, 0));
    }

    #[test]
    fn invalid_input_is_none() {
        assert_eq!(mean_interval(&[], 0.95, 999, 1), None);
        assert_eq!(mean_interval(&[1.0, 2.0], 0.95, 999, 1), None);
        assert_eq!(mean_interval(&[1.0, 2.0, f64::NAN], 0.95, 999, 1), None);
        assert_eq!(mean_interval(&[1.0, 2.0, f64::NEG_INFINITY], 0.95, 999, 1), None);
        assert_eq!(mean_interval(&[f64::MAX, f64::MAX, 1.0], 0.95, 999, 1), None);
        for level in [0.0, 1.0, -0.5, 1.5, f64::NAN] {
            assert_eq!(mean_interval(&DATA, level, 999, 1), None, "level {level}");
        }
        assert_eq!(mean_interval(&DATA, 0.95, 0, 1), None);
    }

    #[test]
    fn tiny_values_are_not_mistaken_for_equal_ones() {
        let tiny: Vec<f64> = DATA.iter().map(|x| x * 1e-200).collect();
        let iv = mean_interval(&tiny, 0.95, 999, 7).expect("8 finite values");
        let reference = mean_interval(&DATA, 0.95, 999, 7).expect("8 finite values");
        assert!(iv.low < iv.high);
        assert!((iv.low / 1e-200 - reference.low).abs() < 1e-9);
        assert!((iv.high / 1e-200 - reference.high).abs() < 1e-9);
    }

    #[test]
    fn drops_degenerate_resamples_and_counts_them() {
        // n = 3: a resample repeats one value with probability 3/27 = 1/9.
        let iv = mean_interval(&[1.0, 2.0, 4.0], 0.95, 9000, 3).expect("3 finite values");
        let share = iv.dropped_resamples as f64 / 9000.0;
        // Binomial sd of the share is 0.0033; 5 sd either side.
        assert!((share - 1.0 / 9.0).abs() < 0.017, "dropped share {share}");
    }

    #[test]
    fn ties_put_the_mean_at_an_end() {
        // Kept resamples hold k ≥ 1 copies of 100; k = 1 reproduces the data (t* = 0 exactly)
        // and k ≥ 2 has m* > m, so no t* is negative and the upper end is m itself.
        let data = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 100.0];
        let iv = mean_interval(&data, 0.95, 999, 11).expect("8 finite values");
        assert_eq!(iv.t_low, 0.0);
        assert_eq!(iv.high, iv.mean);
        assert!(iv.low < iv.mean);
    }

    #[test]
    fn few_resamples_can_miss_the_mean() {
        // With 2 resamples the "quantiles" are just the two t*'s; both on one side of 0 — a
        // coin flip — leaves m outside. Search a few seeds for such a case to show it happens.
        let missed = (0..64).filter_map(|seed| mean_interval(&DATA, 0.95, 2, seed)).any(|iv| {
            let outside = iv.mean < iv.low || iv.high < iv.mean;
            assert_eq!(outside, iv.t_low > 0.0 || iv.t_high < 0.0);
            outside
        });
        assert!(missed);
    }

    #[test]
    fn scale_and_shift_carry_through() {
        // cm → m and an offset: the interval follows up to rounding.
        let a = mean_interval(&DATA, 0.95, 999, 5).expect("8 finite values");
        let moved: Vec<f64> = DATA.iter().map(|x| 0.01 * x + 40.0).collect();
        let b = mean_interval(&moved, 0.95, 999, 5).expect("8 finite values");
        assert!((b.low - (0.01 * a.low + 40.0)).abs() < 1e-9);
        assert!((b.high - (0.01 * a.high + 40.0)).abs() < 1e-9);
    }
}
