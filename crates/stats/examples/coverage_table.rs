//! The coverage table of the `bootstrap` module's doc: 20 000 simulated studies per row
//! (binomial SE ±0.0015), bootstrap-t at B = 999 and at the tests' B = 399, percentile at
//! B = 999. About a minute:
//! `cargo run -p hagfish-stats --release --example coverage_table`.

#[path = "../tests/integration/coverage.rs"]
mod coverage;
#[path = "../tests/integration/samples.rs"]
mod samples;

use coverage::measure;
use samples::Population;

/// Resamples of the asserted tests (`tests/integration/bootstrap_coverage.rs`).
const TEST_RESAMPLES: usize = 399;

fn main() {
    println!(
        "| data | n | bootstrap-t, B = 999 | bootstrap-t, B = {TEST_RESAMPLES} | percentile, B = 999 |"
    );
    println!("|---|---|---|---|---|");
    for population in [Population::Normal, Population::Exponential] {
        for n in [3, 5, 8, 15, 30] {
            let wide = measure(population, n, 20_000, 999, true);
            let narrow = measure(population, n, 20_000, TEST_RESAMPLES, false);
            let p = wide.percentile.unwrap_or(f64::NAN);
            println!(
                "| {population:?} | {n} | {:.3} | {:.3} | {p:.3} |",
                wide.bootstrap_t, narrow.bootstrap_t
            );
        }
    }
}
