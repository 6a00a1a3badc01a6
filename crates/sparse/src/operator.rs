//! The tree factor as the effective mass of a `hagfish-solver` problem: the contact-space
//! solve needs only `L⁻¹`, `L⁻ᵀ` (on each column of `Cᵀ` and on `f̃`) and `M̃x`, all O(bodies)
//! per column here.
//!
//! `L⁻¹` runs on batches of up to [`LANES`] columns, copied interleaved into the factor's
//! lane buffer: one leaf-to-root pass reads the factor once for the whole batch, and a batch
//! of rows that vanish past body k visits the bodies 0..=k only.

use std::ops::Range;

use faer::MatMut;
use faer::reborrow::{Reborrow, ReborrowMut};
use hagfish_solver::{FactoredMass, MassOperator};

use crate::factor::{LANES, TreeFactor};

impl FactoredMass for TreeFactor {
    /// `x ← L⁻¹x` (the leaf-to-root pass) in batches of `LANES` (four) columns.
    fn solve_lower(&self, x: MatMut<'_, f64>) {
        let n = x.nrows();
        solve_lower_batched(self, x, |_| n);
    }

    /// `x ← L⁻ᵀx` column by column (the root-to-leaf pass).
    fn solve_upper(&self, mut x: MatMut<'_, f64>) {
        for j in 0..x.ncols() {
            for_column(x.rb_mut().col_mut(j), |c| self.solve_upper_column(c));
        }
    }

    /// The tree factor keeps the zeros past the joint of entry `end − 1`: the end of that
    /// joint's DOFs (0 when `end` is 0).
    fn lower_support(&self, end: usize) -> Option<usize> {
        Some(TreeFactor::lower_support(self, end))
    }

    /// `x ← L⁻¹x` in batches of `LANES` (four) columns, each over the bodies of its largest
    /// support only.
    fn solve_lower_supported(&self, x: MatMut<'_, f64>, support: &[usize]) {
        solve_lower_batched(self, x, |j| support[j]);
    }

    /// The pass of six unit biases, f = 0, through a run of whole joints of a chain (each body
    /// the parent of the next, none but the last with children elsewhere); false for any
    /// other range.
    fn wrench_span(&self, range: Range<usize>, out: MatMut<'_, f64>) -> bool {
        TreeFactor::wrench_span(self, range, out)
    }
}

impl MassOperator for TreeFactor {
    /// The number of reduced DOFs n.
    fn dofs(&self) -> usize {
        TreeFactor::dofs(self)
    }

    /// `out ← M̃x = Jᵀ Ĩ J x + K̃ x`.
    fn apply(&self, x: &[f64], out: &mut [f64]) {
        TreeFactor::apply(self, x, out);
    }
}

/// `x ← L⁻¹x` by batches of up to [`LANES`] columns; column j vanishes from entry
/// `support(j)` on, a value of [`TreeFactor::lower_support`] (n: no zeros to skip).
fn solve_lower_batched(
    factor: &TreeFactor,
    mut x: MatMut<'_, f64>,
    support: impl Fn(usize) -> usize,
) {
    let mut buffer = factor.lane_columns();
    for first in (0..x.ncols()).step_by(LANES) {
        let count = LANES.min(x.ncols() - first);
        let end = (first..first + count).map(&support).max().unwrap_or(0);
        let batch = x.rb_mut().subcols_mut(first, count).subrows_mut(0, end);
        match count {
            1 => solve_lower_batch::<1>(factor, batch, &mut buffer, end),
            _ => solve_lower_batch::<LANES>(factor, batch, &mut buffer, end),
        }
    }
}

/// One batch (at most K columns of `support` rows): copied interleaved into `buffer` (lanes
/// beyond the batch zero), solved, copied back.
fn solve_lower_batch<const K: usize>(
    factor: &TreeFactor,
    mut batch: MatMut<'_, f64>,
    buffer: &mut [f64],
    support: usize,
) {
    let (lanes, _) = buffer[..support * K].as_chunks_mut::<K>();
    if batch.ncols() < K {
        lanes.fill([0.0; K]);
    }
    for k in 0..batch.ncols() {
        for (lane, value) in lanes.iter_mut().zip(batch.rb().col(k).iter()) {
            lane[k] = *value;
        }
    }
    factor.solve_lower_lanes(lanes, support);
    for k in 0..batch.ncols() {
        for (value, lane) in batch.rb_mut().col_mut(k).iter_mut().zip(lanes.iter()) {
            *value = lane[k];
        }
    }
}

/// Runs `f` on the column as a contiguous slice (faer columns of a column-major matrix are),
/// or on a copy when the view is strided.
fn for_column(mut column: faer::ColMut<'_, f64>, f: impl Fn(&mut [f64])) {
    if let Some(slice) = column.rb_mut().try_as_col_major_mut() {
        f(slice.as_slice_mut());
        return;
    }
    let mut copy: Vec<f64> = column.rb().iter().copied().collect();
    f(&mut copy);
    for (dst, src) in column.iter_mut().zip(&copy) {
        *dst = *src;
    }
}
