//! Small dense kernels on slices, and views of slices as faer columns.
//!
//! Vectors in the workspaces are plain `Vec<f64>` (grow-only, no allocation once sized);
//! these helpers let faer's blocked kernels act on them as n × 1 matrices.

use faer::{Mat, MatMut, MatRef};

use crate::error::SolverError;

/// Makes room in `buffer` for `capacity` elements in all, or says that `what` could not be
/// allocated (never aborts on a failed allocation).
pub(crate) fn try_capacity<T>(
    buffer: &mut Vec<T>,
    capacity: usize,
    what: &'static str,
) -> Result<(), SolverError> {
    buffer
        .try_reserve(capacity.saturating_sub(buffer.len()))
        .map_err(|_| allocation(what, capacity, 1, size_of::<T>()))
}

/// Makes room in `matrix` for `rows` × `cols` entries, or says that `what` could not be
/// allocated (never aborts on a failed allocation).
pub(crate) fn try_matrix_capacity(
    matrix: &mut Mat<f64>,
    rows: usize,
    cols: usize,
    what: &'static str,
) -> Result<(), SolverError> {
    matrix.try_reserve(rows, cols).map_err(|_| allocation(what, rows, cols, size_of::<f64>()))
}

/// The error of a failed allocation of `what`, `rows` × `cols` values of `size` bytes.
fn allocation(what: &str, rows: usize, cols: usize, size: usize) -> SolverError {
    let bytes = (rows as u64).saturating_mul(cols as u64).saturating_mul(size as u64);
    SolverError::Allocation { what: format!("{what} ({rows} × {cols})"), bytes }
}

/// `x` as an n × 1 faer view.
pub(crate) fn column(x: &[f64]) -> MatRef<'_, f64> {
    MatRef::from_column_major_slice(x, x.len(), 1)
}

/// `x` as a mutable n × 1 faer view.
pub(crate) fn column_mut(x: &mut [f64]) -> MatMut<'_, f64> {
    let n = x.len();
    MatMut::from_column_major_slice_mut(x, n, 1)
}

/// A symmetric matrix read entry by entry: the dual matrix W, which is never formed
/// (`contact_space.rs`).
pub(crate) trait Entries {
    /// The entry (i, j), equal to (j, i).
    fn entry(&self, i: usize, j: usize) -> f64;
}

/// Lanes of the partial sums in [`dot`] and [`dot_and_magnitude`]: independent sums the
/// compiler can keep in vector registers (a single running sum cannot be vectorised without
/// reordering it). The order of the additions is fixed, so results are deterministic.
pub(crate) const LANES: usize = 4;

/// xᵀy over the common length of x and y.
pub(crate) fn dot(x: &[f64], y: &[f64]) -> f64 {
    dot_and_magnitude(x, y).0
}

/// (xᵀy, Σᵢ|xᵢyᵢ|) over the common length of x and y, in one pass with [`LANES`] partial sums.
pub(crate) fn dot_and_magnitude(x: &[f64], y: &[f64]) -> (f64, f64) {
    let len = x.len().min(y.len());
    let (x, y) = (x[..len].chunks_exact(LANES), y[..len].chunks_exact(LANES));
    let (x_tail, y_tail) = (x.remainder(), y.remainder());
    let (mut sum, mut magnitude) = ([0.0; LANES], [0.0; LANES]);
    for (a, b) in x.zip(y) {
        for lane in 0..LANES {
            let term = a[lane] * b[lane];
            sum[lane] += term;
            magnitude[lane] += term.abs();
        }
    }
    for (lane, (a, b)) in x_tail.iter().zip(y_tail).enumerate() {
        let term = a * b;
        sum[lane] += term;
        magnitude[lane] += term.abs();
    }
    let total = |s: [f64; LANES]| (s[0] + s[1]) + (s[2] + s[3]);
    (total(sum), total(magnitude))
}

/// Columns of `a` per pass of [`add_product_and_size`]: y and s are read and written once for
/// four columns instead of once for each.
const COLUMNS_PER_PASS: usize = 4;

/// y ← y + A x and s ← s + |A| x_size (p × p, in place), over the columns j with xⱼ ≠ 0 (a
/// column whose x cancelled to 0 adds nothing to s either): the dual gradient's product and
/// its rounding scale (`contact_space/dual_matrix.rs`). Four columns at a time, each entry
/// summed as ((a₀x₀ + a₁x₁) + a₂x₂) + a₃x₃ before it is added; vectorised with AVX2 where the
/// CPU has it (`pulp`'s runtime dispatch), with the same additions in the same order, so the
/// result is the same on any x86-64.
pub(crate) fn add_product_and_size(
    a: &Mat<f64>,
    x: &[f64],
    x_size: &[f64],
    y: &mut [f64],
    s: &mut [f64],
) {
    pulp::Arch::new().dispatch(ProductAndSize { a, x, x_size, y, s });
}

/// The operands of [`add_product_and_size`], as `pulp` dispatches them.
struct ProductAndSize<'a> {
    a: &'a Mat<f64>,
    x: &'a [f64],
    x_size: &'a [f64],
    y: &'a mut [f64],
    s: &'a mut [f64],
}

impl pulp::WithSimd for ProductAndSize<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Self { a, x, x_size, y, s } = self;
        let rows = y.len();
        let column = |j: usize| &a.col_as_slice(j)[..rows];
        let mut batch = [(0, 0.0, 0.0); COLUMNS_PER_PASS];
        let mut count = 0;
        for (j, (&value, &size)) in x.iter().zip(x_size).enumerate() {
            if value == 0.0 {
                continue;
            }
            batch[count] = (j, value, size);
            count += 1;
            if count < COLUMNS_PER_PASS {
                continue;
            }
            count = 0;
            let [(c0, x0, z0), (c1, x1, z1), (c2, x2, z2), (c3, x3, z3)] = batch;
            let columns = column(c0).iter().zip(column(c1)).zip(column(c2)).zip(column(c3));
            for ((g, t), (((a0, a1), a2), a3)) in y.iter_mut().zip(s.iter_mut()).zip(columns) {
                *g += a0 * x0 + a1 * x1 + a2 * x2 + a3 * x3;
                *t += a0.abs() * z0 + a1.abs() * z1 + a2.abs() * z2 + a3.abs() * z3;
            }
        }
        for &(j, value, size) in &batch[..count] {
            for ((g, t), w) in y.iter_mut().zip(s.iter_mut()).zip(column(j)) {
                *g += w * value;
                *t += w.abs() * size;
            }
        }
    }
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
