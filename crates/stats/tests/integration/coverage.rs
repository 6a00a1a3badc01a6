//! Coverage of the bootstrap intervals over simulated studies: shared by the asserted tests
//! (`bootstrap_coverage.rs`) and the table of the `bootstrap` module's doc
//! (`cargo run -p hagfish-stats --release --example coverage_table`).

use hagfish_stats::{mean_interval, quantile_sorted};
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};

use crate::samples::Population;

/// The level of every interval measured.
pub const LEVEL: f64 = 0.95;

/// Shares of studies whose interval covered the population mean.
pub struct Coverage {
    /// Share covered by the bootstrap-t interval.
    pub bootstrap_t: f64,
    /// Share covered by the percentile interval, if measured.
    pub percentile: Option<f64>,
}

/// The percentile bootstrap interval [m*_((1−level)/2), m*_((1+level)/2)] (type-7
/// quantiles of the resample means) — here only, to measure what the crate does not use.
/// Indices are ⌊u·n⌋ from 32-bit draws u (bias below n/2³², irrelevant here).
fn percentile_interval(values: &[f64], resamples: usize, seed: u64) -> (f64, f64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = values.len();
    let mut means = Vec::with_capacity(resamples);
    for _ in 0..resamples {
        let mut sum = 0.0;
        for _ in 0..n {
            sum += values[((u64::from(rng.next_u32()) * n as u64) >> 32) as usize];
        }
        means.push(sum / n as f64);
    }
    means.sort_by(f64::total_cmp);
    let q = |p| quantile_sorted(&means, p).expect("resamples > 0");
    (q((1.0 - LEVEL) / 2.0), q((1.0 + LEVEL) / 2.0))
}

/// Runs `studies` seeded studies of `n` draws from `population`, each with its own
/// bootstrap seed and `resamples` resamples, and counts the intervals that contain the
/// population mean (the percentile one too if `percentile`).
pub fn measure(
    population: Population,
    n: usize,
    studies: usize,
    resamples: usize,
    percentile: bool,
) -> Coverage {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5eed_0000 + n as u64);
    let truth = population.mean();
    let (mut hits_t, mut hits_p) = (0_usize, 0_usize);
    let mut values = vec![0.0; n];
    for _ in 0..studies {
        values.iter_mut().for_each(|x| *x = population.draw(&mut rng));
        let seed = rng.next_u64();
        let iv = mean_interval(&values, LEVEL, resamples, seed).expect("continuous data");
        hits_t += usize::from(iv.low <= truth && truth <= iv.high);
        if percentile {
            let (low, high) = percentile_interval(&values, resamples, seed ^ 0xface);
            hits_p += usize::from(low <= truth && truth <= high);
        }
    }
    let share = |hits: usize| hits as f64 / studies as f64;
    Coverage { bootstrap_t: share(hits_t), percentile: percentile.then(|| share(hits_p)) }
}
