//! W read without forming it: its entries and the dual gradient Wλ − r from W_R.
//!
//! With E the m × p matrix of the rows' terms (row i = Σ_t w_t · reduced column j_t) and E_c
//! the compliances of the combinations (those of rows of their own are on W_R's diagonal):
//!
//! - Wᵢⱼ = Σ_s Σ_t w_s w_t W_R[j_s, j_t] (+ εᵢ when i = j is a combination), summed with the
//!   lower row index outside so that W is exactly symmetric (the active set reads either
//!   triangle). For rows of their own it is W_R's entry itself.
//! - Wλ − r = E (W_R (Eᵀλ)) + E_cλ − r, at O(m + p · nnz(Eᵀλ)) instead of O(m · nnz(λ)): a
//!   pyramid's 8 edges share one column of W_R instead of 8 of W.
//!
//! For a problem without combinations (E = I) both are what the formed W gave, bit for bit:
//! the gradient of a row of its own starts at −rᵢ in its reduced column and adds the same
//! products in the same order.

use super::ContactSpace;
use crate::error::SolverError;
use crate::linalg::{Entries, add_product_and_size, try_capacity, zeroed};

/// Scratch of the products through the reduced columns ([`ContactSpace::gradient`],
/// [`ContactSpace::lift`], [`ContactSpace::row_products`]), p each: Eᵀλ, |E|ᵀ|λ|, the
/// reduced gradient and its magnitude, or the reduced columns' products with q̇ and their
/// sizes (grow-only).
#[derive(Debug, Default)]
pub(crate) struct ReducedScratch {
    lambda: Vec<f64>,
    lambda_size: Vec<f64>,
    pub(super) gradient: Vec<f64>,
    pub(super) magnitude: Vec<f64>,
}

impl ReducedScratch {
    /// Room for problems of up to `rows` rows (there are at most as many reduced columns).
    pub(crate) fn try_reserve(&mut self, rows: usize) -> Result<(), SolverError> {
        let buffers =
            [&mut self.lambda, &mut self.lambda_size, &mut self.gradient, &mut self.magnitude];
        for buffer in buffers {
            try_capacity(buffer, rows, "a reduced-column vector")?;
        }
        Ok(())
    }
}

impl Entries for ContactSpace {
    /// Wᵢⱼ (module docs).
    fn entry(&self, i: usize, j: usize) -> f64 {
        let (a, b) = (i.min(j), i.max(j));
        let (terms_a, terms_b) = (self.reduced.terms(a), self.reduced.terms(b));
        let w = &self.w;
        let sum = match (terms_a, terms_b) {
            (&[(c, _)], &[(d, _)]) => w[(c, d)],
            _ => terms_a
                .iter()
                .map(|&(c, wc)| wc * terms_b.iter().map(|&(d, wd)| wd * w[(c, d)]).sum::<f64>())
                .sum(),
        };
        if a == b && self.reduced.own_column(a).is_none() { sum + self.compliance[a] } else { sum }
    }
}

impl ContactSpace {
    /// Eᵀλ (p) in `scratch`: a row of its own's λᵢ copied, a combination's w_t λᵢ added to its
    /// bases.
    pub(super) fn fold<'s>(&self, lambda: &[f64], scratch: &'s mut ReducedScratch) -> &'s [f64] {
        let folded = &mut scratch.lambda;
        zeroed(folded, self.reduced.len());
        for (i, &value) in lambda.iter().enumerate() {
            match self.reduced.own_column(i) {
                Some(column) => folded[column] = value,
                None => {
                    for &(column, weight) in self.reduced.terms(i) {
                        folded[column] += weight * value;
                    }
                }
            }
        }
        folded
    }

    /// `gradient` ← Wλ − r and `magnitude` ← |r| + |E| |W_R| |E|ᵀ|λ| + |E_cλ| (m each), through
    /// W_R (module docs): the size of the products this sum rounds, and a bound on
    /// |rᵢ| + Σⱼ|Wᵢⱼλⱼ| from above (equal to it without combinations).
    pub(crate) fn gradient(
        &self,
        lambda: &[f64],
        scratch: &mut ReducedScratch,
        gradient: &mut [f64],
        magnitude: &mut [f64],
    ) {
        let p = self.reduced.len();
        self.fold(lambda, scratch);
        let ReducedScratch { lambda: folded, lambda_size, gradient: reduced, magnitude: size } =
            scratch;
        zeroed(lambda_size, p);
        for (i, &value) in lambda.iter().enumerate() {
            for &(column, weight) in self.reduced.terms(i) {
                lambda_size[column] += weight.abs() * value.abs();
            }
        }
        zeroed(reduced, p);
        zeroed(size, p);
        for column in 0..p {
            if let Some(i) = self.reduced.own_row(column) {
                reduced[column] = -self.r[i];
                size[column] = self.r[i].abs();
            }
        }
        add_product_and_size(&self.w, folded, lambda_size, reduced, size);
        for (i, (g, s)) in gradient.iter_mut().zip(magnitude.iter_mut()).enumerate() {
            if let Some(column) = self.reduced.own_column(i) {
                (*g, *s) = (reduced[column], size[column]);
                continue;
            }
            let spring = self.compliance[i] * lambda[i];
            let terms = self.reduced.terms(i);
            *g = -self.r[i] + terms.iter().map(|&(j, w)| w * reduced[j]).sum::<f64>() + spring;
            *s = self.r[i].abs()
                + terms.iter().map(|&(j, w)| w.abs() * size[j]).sum::<f64>()
                + spring.abs();
        }
    }
}
