//! One row's coefficients cᵢ, read where they are stored: a row of its own is a slice; a
//! combination of three bases (`rows.rs`) is written out entry by entry as it is read,
//! cᵢⱼ = w₀g₀ⱼ + w₁g₁ⱼ + w₂g₂ⱼ below its bases' extent e and 0 from e on. A friction pyramid's
//! eight edge rows are never expanded as a whole: most of them rest on their bound with
//! λᵢ = 0 and are read by nobody (the contact-space solve reads the bases).
//!
//! Every reader computes each entry with the same operations in the same order as a written-out
//! row would hold it, so a product over a combination equals the product over its
//! written-out coefficients bit for bit (the tail's entries are the same zeros).

use crate::linalg::{LANES, dot_and_magnitude};

/// Row i's coefficients as stored (from [`Rows::row`](crate::Rows::row)).
#[derive(Debug, Clone, Copy)]
pub struct RowCoefficients<'a>(Stored<'a>);

/// Where the coefficients are.
#[derive(Debug, Clone, Copy)]
enum Stored<'a> {
    /// A row of its own.
    Own(&'a [f64]),
    /// Σₖ weights[k] · bases[k] on `..extent`, zero after it (n = the bases' length).
    Combination { bases: [&'a [f64]; 3], weights: [f64; 3], extent: usize },
}

impl<'a> RowCoefficients<'a> {
    /// A row of its own.
    pub(crate) fn own(coefficients: &'a [f64]) -> Self {
        Self(Stored::Own(coefficients))
    }

    /// `Σₖ weights[k] · bases[k]`, whose bases vanish from `extent` on.
    pub(crate) fn combination(bases: [&'a [f64]; 3], weights: [f64; 3], extent: usize) -> Self {
        Self(Stored::Combination { bases, weights, extent })
    }

    /// Number of coefficients n.
    pub fn len(&self) -> usize {
        match self.0 {
            Stored::Own(c) => c.len(),
            Stored::Combination { bases, .. } => bases[0].len(),
        }
    }

    /// True for a row over no velocities.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Coefficient cᵢⱼ, or `None` for j ≥ n.
    pub fn get(&self, j: usize) -> Option<f64> {
        match self.0 {
            Stored::Own(c) => c.get(j).copied(),
            Stored::Combination { bases: [g0, g1, g2], weights: w, extent } if j < extent => {
                Some(w[0] * g0[j] + w[1] * g1[j] + w[2] * g2[j])
            }
            Stored::Combination { bases, .. } => (j < bases[0].len()).then_some(0.0),
        }
    }

    /// The coefficients cᵢ₀ … cᵢₙ₋₁ in order.
    pub fn iter(&self) -> impl Iterator<Item = f64> + 'a {
        let row = *self;
        (0..row.len()).filter_map(move |j| row.get(j))
    }

    /// The coefficients written out (allocates: for tests, references and error reports).
    pub fn to_vec(&self) -> Vec<f64> {
        self.iter().collect()
    }

    /// `y ← y + a cᵢ` over the entries of y (its length ≤ n: a row's support), each entry
    /// `y_j + a·c_ij` as [`axpy`](crate::linalg::axpy) over the written-out row.
    pub(crate) fn add_scaled_to(&self, a: f64, y: &mut [f64]) {
        match self.0 {
            Stored::Own(c) => crate::linalg::axpy(a, c, y),
            Stored::Combination { bases: [g0, g1, g2], weights: w, extent } => {
                let (used, zero) = y.split_at_mut(extent.min(y.len()));
                let entries = g0.iter().zip(g1).zip(g2);
                for (yj, ((p, q), r)) in used.iter_mut().zip(entries) {
                    *yj += a * (w[0] * p + w[1] * q + w[2] * r);
                }
                // Adds ±0 as the written-out zeros do (−0 + 0 is +0: kept bit for bit).
                zero.iter_mut().for_each(|yj| *yj += a * 0.0);
            }
        }
    }

    /// (cᵢᵀy, Σⱼ|cᵢⱼyⱼ|) over the entries of y, as
    /// [`dot_and_magnitude`](crate::linalg::dot_and_magnitude) over the written-out row: entry
    /// j in lane j mod [`LANES`], so bit for bit the same.
    pub(crate) fn dot_and_magnitude(&self, y: &[f64]) -> (f64, f64) {
        match self.0 {
            Stored::Own(c) => dot_and_magnitude(c, y),
            Stored::Combination { bases, weights, extent } => {
                combination_dot_and_magnitude(bases, weights, extent, y)
            }
        }
    }
}

/// [`RowCoefficients::dot_and_magnitude`] of a combination: [`LANES`] entries written out at
/// a time, then summed into their lanes as the slice version does.
fn combination_dot_and_magnitude(
    [g0, g1, g2]: [&[f64]; 3],
    w: [f64; 3],
    extent: usize,
    y: &[f64],
) -> (f64, f64) {
    let len = y.len().min(g0.len());
    let mut chunk = [0.0; LANES];
    let (mut sum, mut magnitude) = ([0.0; LANES], [0.0; LANES]);
    for start in (0..len).step_by(LANES) {
        let width = LANES.min(len - start);
        for (lane, c) in chunk[..width].iter_mut().enumerate() {
            let j = start + lane;
            *c = if j < extent { w[0] * g0[j] + w[1] * g1[j] + w[2] * g2[j] } else { 0.0 };
        }
        for lane in 0..width {
            let term = chunk[lane] * y[start + lane];
            sum[lane] += term;
            magnitude[lane] += term.abs();
        }
    }
    let total = |s: [f64; LANES]| (s[0] + s[1]) + (s[2] + s[3]);
    (total(sum), total(magnitude))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A combination with awkward values: every product over it equals the product over the
    /// written-out row bit for bit, for supports of every length.
    #[test]
    fn a_combination_reads_as_its_written_out_row() {
        let n = 11;
        let value = |k: usize| ((k * 7919) % 23) as f64 / 7.0 - 1.3;
        let bases: Vec<Vec<f64>> = (0..3)
            .map(|b| (0..n).map(|j| if j < 8 { value(b * n + j) } else { 0.0 }).collect())
            .collect();
        let weights = [0.31, -1.7, 2.9e-3];
        let row = RowCoefficients::combination([&bases[0], &bases[1], &bases[2]], weights, 8);
        let written: Vec<f64> = (0..n)
            .map(|j| weights[0] * bases[0][j] + weights[1] * bases[1][j] + weights[2] * bases[2][j])
            .collect();
        assert_eq!(row.to_vec(), written);
        assert_eq!((row.len(), row.get(n - 1), row.get(n)), (n, Some(0.0), None));
        // A −0 in the zero tail: a written-out row adds +0 to it and makes it +0.
        let mut y: Vec<f64> = (0..n).map(|j| value(100 + j) * 1e3).collect();
        y[9] = -0.0;
        let own = RowCoefficients::own(&written);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for support in 0..=n {
            let products = [row, own].map(|r| r.dot_and_magnitude(&y[..support]));
            assert_eq!(products[0], products[1], "support {support}");
            let [mut from_combination, mut from_row] = [y.clone(), y.clone()];
            row.add_scaled_to(0.37, &mut from_combination[..support]);
            own.add_scaled_to(0.37, &mut from_row[..support]);
            assert_eq!(bits(&from_combination), bits(&from_row), "support {support}");
        }
    }
}
