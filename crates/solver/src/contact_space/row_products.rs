//! The rows' products cᵢᵀq̇ read through the reduced columns: Cq̇ = E(C_R q̇).
//!
//! A pyramid's 8 edge rows are combinations of their contact's 3 bases (`reduced_rows.rs`),
//! so the products of the p reduced columns give all m rows' at O(p · n) instead of
//! O(m · n): cᵢᵀq̇ = Σ_t w_t (g_{j_t}ᵀq̇), with the size Σ_t |w_t| Σⱼ|g_{j_t,j} q̇ⱼ|, a bound
//! on Σⱼ|cᵢⱼq̇ⱼ| from above (the rounding scale of the primal residuals, as for the dual
//! gradient's in `dual_matrix.rs`). A row of its own is its column's product itself, summed
//! as [`dot_and_magnitude`] sums the row over its support, bit for bit.

use super::{ContactSpace, ReducedScratch};
use crate::linalg::dot_and_magnitude;
use crate::rows::Rows;

impl ContactSpace {
    /// (cᵢᵀq̇, its size) for every row of `rows` (those of the last build) into `out` (m
    /// pairs; grow-only; module docs), the reduced columns' in `scratch`.
    pub(crate) fn row_products(
        &self,
        rows: &Rows,
        qdot: &[f64],
        scratch: &mut ReducedScratch,
        out: &mut Vec<(f64, f64)>,
    ) {
        let (products, sizes) = (&mut scratch.gradient, &mut scratch.magnitude);
        products.clear();
        sizes.clear();
        for (j, &support) in self.column_support.iter().enumerate() {
            let (product, size) = dot_and_magnitude(self.reduced.column(rows, j), &qdot[..support]);
            products.push(product);
            sizes.push(size);
        }
        out.clear();
        out.extend((0..rows.len()).map(|i| match self.reduced.own_column(i) {
            Some(j) => (products[j], sizes[j]),
            None => {
                let terms = self.reduced.terms(i).iter();
                terms.fold((0.0, 0.0), |(product, size), &(j, w)| {
                    (product + w * products[j], size + w.abs() * sizes[j])
                })
            }
        }));
    }
}
