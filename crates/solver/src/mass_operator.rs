//! The effective mass as the solver sees it: a dense matrix that the workspace factors, or an
//! operator that brings its own factor (the sparse maximal-coordinate backend of
//! `hagfish-sparse`, whose tree-structured factor is O(n) where the dense Cholesky is O(n³)).
//!
//! Every path of the contact-space solve needs M̃ only through a square-root split
//! M̃ = L Lᵀ (x ← L⁻¹x, x ← L⁻ᵀx: Y = L⁻¹Cᵀ, W = YᵀY, q̇ = L⁻ᵀ(z + Yλ)) and through the
//! product M̃x (residuals and refinement). L need not be triangular: any L with M̃ = L Lᵀ
//! gives the same W, r and q̇.

use std::ops::Range;

use faer::{Mat, MatMut, MatRef};

/// A factored effective mass M̃ = L Lᵀ, applied through its factor.
pub trait FactoredMass: core::fmt::Debug {
    /// x ← L⁻¹x for every column of x (n rows).
    fn solve_lower(&self, x: MatMut<'_, f64>);

    /// x ← L⁻ᵀx for every column of x (n rows).
    fn solve_upper(&self, x: MatMut<'_, f64>);

    /// Where L⁻¹ keeps trailing zeros: for every x that vanishes from entry `end` on, L⁻¹x
    /// vanishes from the returned entry e ≥ `end` on; `None` when L⁻¹x may fill them (the
    /// default). Constraint rows in reduced coordinates rooted at the head vanish past their
    /// body's DOFs: an upper-triangular L keeps exactly those zeros (e = `end`, the dense
    /// factor), a factor eliminated leaf to root keeps those past the joint of entry `end` − 1.
    fn lower_support(&self, end: usize) -> Option<usize> {
        let _ = end;
        None
    }

    /// x ← L⁻¹x for columns x_j that vanish from entry `support[j]` on, `support`
    /// non-increasing (one entry per column, each ≤ n, each a value of
    /// [`lower_support`](Self::lower_support), so L⁻¹x_j vanishes there too). A factor that
    /// keeps trailing zeros skips them (for the dense factor O(Σⱼ supportⱼ²) instead of O(n²)
    /// per column). Default: [`solve_lower`](Self::solve_lower), ignoring the support.
    fn solve_lower_supported(&self, x: MatMut<'_, f64>, support: &[usize]) {
        let _ = support;
        self.solve_lower(x);
    }

    /// The span of L⁻¹ on the DOFs `range` for rows that are one wrench's generalized force
    /// there (`contact_space/compressed_spans.rs`): writes into `out` (`range.len()` × 6) six
    /// columns whose span holds `(L⁻¹c)[range]` for every c with c_a = s_aᵀF on `range` for one
    /// wrench F (whatever c is past the range), and returns true; false (the default) when
    /// the factor has no such span for the range. The tree factor has one on every run of
    /// whole joints of a chain: the leaf-to-root pass carries one six-vector through it.
    fn wrench_span(&self, range: Range<usize>, out: MatMut<'_, f64>) -> bool {
        let _ = (range, out);
        false
    }
}

/// An effective mass given as an operator with its own factor: M̃x and the split of
/// [`FactoredMass`]. The implementer guarantees that M̃ is symmetric positive definite and that
/// both agree (M̃ = L Lᵀ).
pub trait MassOperator: FactoredMass {
    /// Number of DOFs n.
    fn dofs(&self) -> usize;

    /// out ← M̃x (both of length n).
    fn apply(&self, x: &[f64], out: &mut [f64]);
}

/// M̃ of one [`crate::Problem`].
#[derive(Debug, Clone, Copy)]
pub enum Mass<'a> {
    /// A dense symmetric matrix (n × n), factored by the workspace (dense Cholesky).
    Dense(MatRef<'a, f64>),
    /// An operator with its own factor.
    Operator(&'a dyn MassOperator),
}

/// The dense matrix of an operator, column by column: M̃e_j (n products of O(n) each for the
/// tree operator). Only the clarabel reference needs it.
pub(crate) fn to_dense(operator: &dyn MassOperator) -> Mat<f64> {
    let n = operator.dofs();
    let mut dense = Mat::zeros(n, n);
    let mut unit = vec![0.0; n];
    for j in 0..n {
        unit[j] = 1.0;
        operator.apply(&unit, dense.col_as_slice_mut(j));
        unit[j] = 0.0;
    }
    dense
}
