//! Seeded draws for the simulated studies: uniform, normal and exponential variates from
//! ChaCha8, written out here so the test needs no distribution crate.

/// A uniform f64 on [0, 1): the top 53 bits of a u64 times 2⁻⁵³.
pub fn uniform(rng: &mut impl Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1_u64 << 53) as f64)
}

use rand_chacha::rand_core::Rng;

/// The population a simulated study draws its replicates from.
#[derive(Debug, Clone, Copy)]
pub enum Population {
    /// Normal with mean 10 and sd 2 (symmetric).
    Normal,
    /// Exponential with mean 1 (skewness 2: a long right tail, like a knot that sometimes
    /// stalls).
    Exponential,
}

impl Population {
    /// The population mean that the intervals should cover.
    pub fn mean(self) -> f64 {
        match self {
            Population::Normal => 10.0,
            Population::Exponential => 1.0,
        }
    }

    /// One draw: Box–Muller (cosine branch only) for the normal, −ln(1 − u) for the
    /// exponential.
    pub fn draw(self, rng: &mut impl Rng) -> f64 {
        match self {
            Population::Normal => {
                let u1 = 1.0 - uniform(rng); // (0, 1]: ln is finite
                let u2 = uniform(rng);
                10.0 + 2.0 * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
            }
            Population::Exponential => -(-uniform(rng)).ln_1p(),
        }
    }
}
