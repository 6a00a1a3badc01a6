//! Small dense kernels on slices, and views of slices as faer columns.
//!
//! Vectors in the workspaces are plain `Vec<f64>` (grow-only, no allocation once sized);
//! these helpers let faer's blocked kernels act on them as n × 1 matrices.

use faer::{MatMut, MatRef};

/// `x` as an n × 1 faer view.
pub(crate) fn column(x: &[f64]) -> MatRef<'_, f64> {
    MatRef::from_column_major_slice(x, x.len(), 1)
}

/// `x` as a mutable n × 1 faer view.
pub(crate) fn column_mut(x: &mut [f64]) -> MatMut<'_, f64> {
    let n = x.len();
    MatMut::from_column_major_slice_mut(x, n, 1)
}

/// xᵀy.
pub(crate) fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

/// y ← y + a·x.
pub(crate) fn axpy(a: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// ‖x‖∞ (0 for an empty slice).
pub(crate) fn norm_max(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Resizes `v` to `len` zeros, keeping its capacity (no allocation once large enough).
pub(crate) fn zeroed(v: &mut Vec<f64>, len: usize) {
    v.clear();
    v.resize(len, 0.0);
}
