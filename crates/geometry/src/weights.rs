//! A spline quantity written as a fixed blend of real body centres.
//!
//! A point (or derivative) of the centreline is x = Σ_m w_m c_m over the four control
//! points of its segment. At the ends, the phantom control points c₋₁ = 2c₀ − c₁ and
//! c_N = 2c_{N−1} − c_{N−2} are folded back onto real centres
//! (w on c₀ += 2w₋₁, w on c₁ −= w₋₁, and likewise at the tail), so every spline quantity
//! depends on at most four real bodies. The solver uses these weights for the contact
//! point Jacobian P(u) = Σ_m w_m R_m [0 I₃] J_m.

/// Weights of at most four real bodies whose blend Σ w_m c_m gives a spline quantity.
///
/// Entries `0..len` are valid, sorted by increasing body index, with no index repeated;
/// entries beyond `len` are zero weights on body 0 and must be ignored (or use
/// [`SplineWeights::iter`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplineWeights {
    /// Body indices, ascending, valid up to `len`.
    pub bodies: [usize; SplineWeights::CAPACITY],
    /// Weight of each body, valid up to `len`.
    pub weights: [f64; SplineWeights::CAPACITY],
    /// Number of valid entries (2 to 4; fewer at the ends of short chains).
    pub len: usize,
}

impl SplineWeights {
    /// The most bodies a spline point blends (the four control points of its segment).
    pub const CAPACITY: usize = 4;

    /// The weight 1 on `body` alone: a body centre as a spline-point blend (a wall contact).
    pub fn single(body: usize) -> SplineWeights {
        let mut bodies = [0; SplineWeights::CAPACITY];
        let mut weights = [0.0; SplineWeights::CAPACITY];
        bodies[0] = body;
        weights[0] = 1.0;
        SplineWeights { bodies, weights, len: 1 }
    }

    /// Folds the four segment weights of segment `k` (on c_{k−1}..c_{k+2}) of a chain of
    /// `body_count` ≥ 2 centres onto real bodies, replacing the phantom end points by
    /// their definitions c₋₁ = 2c₀ − c₁ and c_N = 2c_{N−1} − c_{N−2}.
    pub(crate) fn fold(k: usize, body_count: usize, segment_weights: [f64; 4]) -> SplineWeights {
        let mut folded = SplineWeights { bodies: [0; 4], weights: [0.0; 4], len: 0 };
        let last = body_count - 1;
        for (offset, w) in segment_weights.into_iter().enumerate() {
            // Control point index k − 1 + offset, without going below zero.
            match (k + offset).checked_sub(1) {
                None => {
                    folded.add(0, 2.0 * w);
                    folded.add(1, -w);
                }
                Some(index) if index > last => {
                    folded.add(last, 2.0 * w);
                    folded.add(last - 1, -w);
                }
                Some(index) => folded.add(index, w),
            }
        }
        folded
    }

    /// Adds `weight` to `body`, merging with an existing entry and keeping the indices sorted.
    fn add(&mut self, body: usize, weight: f64) {
        let entries = &self.bodies[..self.len];
        match entries.iter().position(|&b| b >= body) {
            Some(at) if self.bodies[at] == body => self.weights[at] += weight,
            position => {
                let at = position.unwrap_or(self.len);
                self.bodies.copy_within(at..self.len, at + 1);
                self.weights.copy_within(at..self.len, at + 1);
                self.bodies[at] = body;
                self.weights[at] = weight;
                self.len += 1;
            }
        }
    }

    /// The valid `(body, weight)` pairs, ascending in body index.
    pub fn iter(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.bodies.iter().copied().zip(self.weights.iter().copied()).take(self.len)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interior_segment_is_unchanged() {
        let w = SplineWeights::fold(3, 10, [0.1, 0.2, 0.3, 0.4]);
        assert_eq!(w.len, 4);
        assert_eq!(w.bodies, [2, 3, 4, 5]);
        assert_eq!(w.weights, [0.1, 0.2, 0.3, 0.4]);
    }

    #[test]
    fn head_phantom_folds_onto_first_two_bodies() {
        // c₋₁ = 2c₀ − c₁ → c₀ gets 0.2 + 2·0.1, c₁ gets 0.3 − 0.1.
        let w = SplineWeights::fold(0, 10, [0.1, 0.2, 0.3, 0.4]);
        let pairs: Vec<_> = w.iter().collect();
        assert_eq!(pairs.len(), 3);
        assert_eq!(pairs[0].0, 0);
        assert!((pairs[0].1 - 0.4).abs() < 1e-15);
        assert_eq!(pairs[1].0, 1);
        assert!((pairs[1].1 - 0.2).abs() < 1e-15);
        assert_eq!(pairs[2], (2, 0.4));
    }

    #[test]
    fn tail_phantom_folds_onto_last_two_bodies() {
        // Segment 8 of 10 bodies: c₁₀ = 2c₉ − c₈.
        let w = SplineWeights::fold(8, 10, [0.1, 0.2, 0.3, 0.4]);
        let pairs: Vec<_> = w.iter().collect();
        assert_eq!(pairs.len(), 3);
        assert_eq!(pairs[0], (7, 0.1));
        assert_eq!(pairs[1].0, 8);
        assert!((pairs[1].1 - (0.2 - 0.4)).abs() < 1e-15);
        assert_eq!(pairs[2].0, 9);
        assert!((pairs[2].1 - (0.3 + 0.8)).abs() < 1e-15);
    }

    #[test]
    fn two_body_chain_folds_both_ends() {
        let w = SplineWeights::fold(0, 2, [0.1, 0.2, 0.3, 0.4]);
        assert_eq!(w.len, 2);
        assert_eq!(&w.bodies[..2], &[0, 1]);
        // Weights still sum to the original sum.
        let sum: f64 = w.iter().map(|(_, x)| x).sum();
        assert!((sum - 1.0).abs() < 1e-15);
    }
}
