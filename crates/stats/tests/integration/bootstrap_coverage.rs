//! How often the 95 % bootstrap-t interval of the mean covers the true mean, over simulated
//! studies of n replicates, against the percentile bootstrap that it replaces.

use crate::coverage::{Coverage, measure};
use crate::samples::Population;

/// Resamples per interval in the asserted tests: (B + 1)·(1 − level)/2 = 10 is an integer,
/// Hall's condition for a finite B to leave the coverage nearly unchanged (P. Hall, Ann.
/// Statist. 14 (1986) 1453; the module doc's table: 0.002–0.004 below B = 999). B = 999
/// would cost 2.5 times as much in a debug build.
const RESAMPLES: usize = 399;
/// Studies per asserted case: the binomial standard error of a coverage near 0.95 is
/// √(0.95·0.05/2000) = 0.0049, so ±3 SE = ±0.015.
const STUDIES: usize = 2000;

/// Asserts a bootstrap-t coverage in [0.95 − 0.015 − `allowance`, 0.95 + 0.015 + 0.01]:
/// ±3 binomial SE, plus the method's own error — O(1/n), larger for skewed data — below, and
/// 0.01 above (at small n the t*'s heavy tails can make the interval long).
fn check(population: Population, n: usize, allowance: f64) -> Coverage {
    let c = measure(population, n, STUDIES, RESAMPLES, population_is_normal_n8(population, n));
    let band = (0.95 - 0.015 - allowance, 0.95 + 0.015 + 0.01);
    println!(
        "{population:?} n = {n}: bootstrap-t covers {:.4}, band [{:.3}, {:.3}]",
        c.bootstrap_t, band.0, band.1
    );
    assert!(
        band.0 <= c.bootstrap_t && c.bootstrap_t <= band.1,
        "{population:?} n = {n}: coverage {} outside {band:?}",
        c.bootstrap_t
    );
    c
}

/// The percentile interval is measured only where the module doc makes its claim.
fn population_is_normal_n8(population: Population, n: usize) -> bool {
    matches!(population, Population::Normal) && n == 8
}

/// Measured (2000 studies, B = 399): bootstrap-t 0.9485, percentile 0.8850. The
/// percentile interval is m ± ≈1.96·σ̂/√n with the plug-in σ̂ = s·√(7/8): it covers about
/// P(|t₇| ≤ 1.96·√(7/8)) = 0.891 (its own resample quantiles shave a little more).
#[test]
fn normal_n8_and_the_percentile_interval() {
    let c = check(Population::Normal, 8, 0.01);
    let percentile = c.percentile.expect("measured at n = 8");
    println!("Normal n = 8: percentile covers {percentile:.4}");
    assert!(percentile < 0.925, "percentile coverage {percentile}: not short after all");
    assert!((c.bootstrap_t - 0.95).abs() < (percentile - 0.95).abs());
}

/// Measured (2000 studies, B = 399): 0.9400.
#[test]
fn normal_n30() {
    check(Population::Normal, 30, 0.01);
}

/// Measured (2000 studies, B = 399): 0.9245. Skewness 2 at n = 8: bootstrap-t's coverage
/// error is O(1/n) (second-order accurate) with a constant that grows with the skew, hence
/// the larger allowance (0.02) below nominal; 20 000 studies give 0.933 (module doc).
#[test]
fn exponential_n8() {
    check(Population::Exponential, 8, 0.02);
}

/// Measured (2000 studies, B = 399): 0.9290. The skew allowance is kept at 0.02: at B = 399
/// the 20 000-study coverage is 0.940 (the module doc), 0.010 below nominal already.
#[test]
fn exponential_n30() {
    check(Population::Exponential, 30, 0.02);
}
