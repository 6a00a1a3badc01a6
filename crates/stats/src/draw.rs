//! Uniform random indices from the seeded ChaCha8 stream, written out so that an interval's
//! bits depend only on ChaCha8's documented, value-stable output and this file — not on a
//! sampling algorithm that a `rand` release or a feature enabled elsewhere in the build (such
//! as `rand/unbiased`) could change.

use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};

/// A stream of uniform, exactly unbiased indices in 0..n from ChaCha8 seeded with a u64.
///
/// Lemire's multiply-and-reject method (D. Lemire, "Fast random integer generation in an
/// interval", ACM Trans. Model. Comput. Simul. 29 (2019) 3) on w-bit pieces x of the
/// stream's u64s (least significant first): x·n = hi·2ʷ + lo; pieces with lo < 2ʷ mod n are
/// rejected, and then hi is uniform on 0..n. w = 16 for n ≤ 2¹⁶ (four indices per u64), else
/// w = 32. Why: the bootstrap needs n·B indices — its hot loop — and a replicate count never
/// needs more than 16 bits, so this spends a quarter of the stream that whole u64s would.
pub(crate) struct IndexDraw {
    rng: ChaCha8Rng,
    n: u64,
    width: u32,
    reject_below: u64,
    pool: u64,
    pooled_bits: u32,
}

impl IndexDraw {
    /// Indices in 0..n from the stream of `seed`; `None` unless 1 ≤ n ≤ 2³².
    pub(crate) fn new(n: usize, seed: u64) -> Option<IndexDraw> {
        let n = u64::try_from(n).ok().filter(|&n| (1..=1 << 32).contains(&n))?;
        let width = if n <= 1 << 16 { 16 } else { 32 };
        Some(IndexDraw {
            rng: ChaCha8Rng::seed_from_u64(seed),
            n,
            width,
            reject_below: (1 << width) % n,
            pool: 0,
            pooled_bits: 0,
        })
    }

    /// The next index in 0..n.
    pub(crate) fn next_index(&mut self) -> usize {
        let mask = (1_u64 << self.width) - 1;
        loop {
            if self.pooled_bits < self.width {
                self.pool = self.rng.next_u64();
                self.pooled_bits = 64;
            }
            let x = self.pool & mask;
            self.pool >>= self.width;
            self.pooled_bits -= self.width;
            let m = x * self.n; // < 2ʷ·n ≤ 2⁶⁴
            if m & mask >= self.reject_below {
                return (m >> self.width) as usize;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::IndexDraw;

    #[test]
    fn in_range_and_roughly_uniform() {
        for n in [7, 100_003] {
            let mut draw = IndexDraw::new(n, 1).expect("1 ≤ n ≤ 2³²");
            let mut counts = [0_u32; 7];
            for _ in 0..70_000 {
                let i = draw.next_index();
                assert!(i < n);
                counts[i % 7] += 1;
            }
            // Each count is about binomial(70 000, 1/7): mean 10 000, sd 93; 5 sd either side.
            assert!(counts.iter().all(|&c| c.abs_diff(10_000) < 465), "n = {n}: {counts:?}");
        }
    }

    #[test]
    fn ranges_at_the_limits() {
        assert!(IndexDraw::new(0, 2).is_none());
        assert!(IndexDraw::new(usize::MAX, 2).is_none());
        let mut one = IndexDraw::new(1, 2).expect("n = 1");
        assert!((0..100).all(|_| one.next_index() == 0));
        let mut widest = IndexDraw::new(1 << 32, 2).expect("n = 2³²");
        assert!((0..100).all(|_| widest.next_index() < 1 << 32));
    }

    #[test]
    fn same_seed_same_indices() {
        let take = |seed| {
            let mut draw = IndexDraw::new(30, seed).expect("n = 30");
            (0..50).map(|_| draw.next_index()).collect::<Vec<_>>()
        };
        assert_eq!(take(9), take(9));
        assert_ne!(take(9), take(10));
    }
}
