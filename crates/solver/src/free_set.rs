//! Cholesky factor of the dual matrix restricted to the free rows, updated in place.
//!
//! The active-set method keeps F, the rows whose multiplier is not at a bound, linearly
//! independent, so W_FF = C_F M̃⁻¹ C_Fᵀ is positive definite, and needs W_FF⁻¹ after every
//! change of F. Instead of refactoring (O(|F|³)) the factor L_F L_Fᵀ = W_FF is updated:
//!
//! - append row i: solve L_F l = W_{F,i} and border L_F with (lᵀ, √d²), d² = Wᵢᵢ − lᵀl. The
//!   pivot d² is returned first ([`FreeSet::border`]) so the caller can reject a row that is
//!   (numerically) dependent on F: d²/Wᵢᵢ is the squared sine of the angle between cᵢ and
//!   span(c_F) in the M̃⁻¹ metric, and z = L_F⁻ᵀl then gives cᵢ = Σ_p z_p c_p;
//! - remove the row at position k: delete row k of L_F, which leaves one super-diagonal entry
//!   per later column, and sweep it out with Givens rotations on column pairs (j, j+1)
//!   (right-multiplying by an orthogonal matrix keeps L_F L_Fᵀ unchanged).
//!
//! Both are O(|F|²).

use crate::error::SolverError;
use crate::linalg::{Entries, try_capacity};

/// Free rows in factor order and the lower-triangular factor (column-major, leading
/// dimension `stride` ≥ number of rows m).
#[derive(Debug, Default)]
pub(crate) struct FreeSet {
    indices: Vec<usize>,
    factor: Vec<f64>,
    stride: usize,
}

impl FreeSet {
    /// Room for a factor of `rows` rows (`rows`², the largest buffer of the active set), so
    /// that [`FreeSet::reset`] to at most `rows` does not allocate.
    pub(crate) fn try_reserve(&mut self, rows: usize) -> Result<(), SolverError> {
        try_capacity(&mut self.indices, rows, "the free rows")?;
        try_capacity(&mut self.factor, rows.saturating_mul(rows), "the free rows' factor")
    }

    /// Empties F for a problem with `rows` rows (reallocates only when `rows` grows).
    pub(crate) fn reset(&mut self, rows: usize) {
        self.indices.clear();
        self.indices.reserve(rows);
        if rows > self.stride {
            self.stride = rows;
            self.factor.clear();
            self.factor.resize(rows * rows, 0.0);
        }
    }

    /// Row indices of F, in factor order.
    pub(crate) fn indices(&self) -> &[usize] {
        &self.indices
    }

    /// The border of row `row` (`w` = W): `l[..|F|]` ← L_F⁻¹W_{F,row}; returns the pivot
    /// d² = W_rr − lᵀl it would get (≈ 0 when c_row is in the span of F's rows).
    pub(crate) fn border(&self, w: &impl Entries, row: usize, l: &mut [f64]) -> f64 {
        let l = &mut l[..self.indices.len()];
        for (lp, &i) in l.iter_mut().zip(&self.indices) {
            *lp = w.entry(i, row);
        }
        self.forward(l);
        w.entry(row, row) - l.iter().map(|v| v * v).sum::<f64>()
    }

    /// Adds row `row` with its border `l` and pivot d² > 0 from [`FreeSet::border`].
    pub(crate) fn push(&mut self, row: usize, l: &[f64], pivot: f64) {
        let k = self.indices.len();
        let stride = self.stride;
        for (j, &lj) in l[..k].iter().enumerate() {
            self.factor[j * stride + k] = lj;
        }
        self.factor[k * stride + k] = pivot.sqrt();
        self.indices.push(row);
    }

    /// Removes the row at position `k` of F (not its row index) and returns its row index.
    pub(crate) fn remove(&mut self, k: usize) -> usize {
        let f = self.indices.len();
        let stride = self.stride;
        // Shift rows k+1.. up by one; column c then holds rows max(k, c−1)..f−1.
        for c in 0..f {
            for i in k.max(c.saturating_sub(1))..f - 1 {
                self.factor[c * stride + i] = self.factor[c * stride + i + 1];
            }
        }
        // Rotate column pairs (j, j+1) to zero the super-diagonal entry (j, j+1).
        for j in k..f - 1 {
            let (a, b) = (self.factor[j * stride + j], self.factor[(j + 1) * stride + j]);
            let radius = a.hypot(b);
            let (cos, sin) = (a / radius, b / radius);
            for i in j..f - 1 {
                let x = self.factor[j * stride + i];
                let y = self.factor[(j + 1) * stride + i];
                self.factor[j * stride + i] = cos * x + sin * y;
                self.factor[(j + 1) * stride + i] = cos * y - sin * x;
            }
        }
        self.indices.remove(k)
    }

    /// x ← W_FF⁻¹x, x in factor order (length |F|).
    pub(crate) fn solve(&self, x: &mut [f64]) {
        self.forward(x);
        self.backward(x);
    }

    /// x ← L_F⁻ᵀx (backward substitution, column oriented).
    pub(crate) fn backward(&self, x: &mut [f64]) {
        let stride = self.stride;
        for j in (0..x.len()).rev() {
            let column = &self.factor[j * stride..j * stride + x.len()];
            let tail: f64 = column[j + 1..].iter().zip(&x[j + 1..]).map(|(l, v)| l * v).sum();
            x[j] = (x[j] - tail) / column[j];
        }
    }

    /// x ← L_F⁻¹x (forward substitution, column oriented).
    fn forward(&self, x: &mut [f64]) {
        let stride = self.stride;
        for j in 0..x.len() {
            let column = &self.factor[j * stride..j * stride + x.len()];
            x[j] /= column[j];
            let xj = x[j];
            for (xi, l) in x[j + 1..].iter_mut().zip(&column[j + 1..]) {
                *xi -= l * xj;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use faer::{ColRef, Mat};

    use super::*;

    impl Entries for Mat<f64> {
        fn entry(&self, i: usize, j: usize) -> f64 {
            self[(i, j)]
        }
    }

    /// A 6 × 6 positive semidefinite W with a duplicated row (rows 2 and 5 equal).
    fn dual_matrix() -> Mat<f64> {
        let y = Mat::from_fn(6, 6, |i, j| {
            let j = if j == 5 { 2 } else { j };
            ((i * 7 + j * 3) % 5) as f64 - 1.5 + if i == j { 2.0 } else { 0.0 }
        });
        y.transpose() * &y
    }

    #[test]
    fn updates_match_the_subsystem() {
        let w = dual_matrix();
        let mut set = FreeSet::default();
        let mut l = vec![0.0; 6];
        set.reset(6);
        for row in [0, 2, 3, 1, 4] {
            let pivot = set.border(&w, row, &mut l);
            assert!(pivot > 1e-3 * w[(row, row)], "row {row}: {pivot}");
            set.push(row, &l, pivot);
        }
        // Row 5 duplicates row 2: its pivot vanishes and z = L⁻ᵀl picks row 2.
        let pivot = set.border(&w, 5, &mut l);
        assert!(pivot.abs() < 1e-12 * w[(5, 5)]);
        set.backward(&mut l[..5]);
        for (p, z) in l[..5].iter().enumerate() {
            assert!((z - if p == 1 { 1.0 } else { 0.0 }).abs() < 1e-9, "{:?}", &l[..5]);
        }
        assert_eq!(set.remove(1), 2);
        assert_eq!(set.remove(2), 1);
        let pivot = set.border(&w, 5, &mut l);
        set.push(5, &l, pivot);
        assert_eq!(set.indices(), &[0, 3, 4, 5]);

        // L_F L_Fᵀ reproduces W_FF ...
        let f = set.indices().len();
        let factor =
            Mat::from_fn(f, f, |i, j| if i >= j { set.factor[j * set.stride + i] } else { 0.0 });
        let product = &factor * factor.transpose();
        for (p, &i) in set.indices().iter().enumerate() {
            for (q, &j) in set.indices().iter().enumerate() {
                assert!((product[(p, q)] - w[(i, j)]).abs() < 1e-12 * (1.0 + w[(i, j)].abs()));
            }
        }
        // ... and the solve inverts it.
        let rhs = [1.0, -2.0, 0.5, 3.0];
        let mut x = rhs;
        set.solve(&mut x);
        let back = &product * ColRef::from_slice(&x);
        for (p, r) in rhs.iter().enumerate() {
            assert!((back[p] - r).abs() < 1e-10, "{} vs {r}", back[p]);
        }
    }
}
