//! The tree factor as the effective mass of a `hagfish-solver` problem: the contact-space
//! solve needs only `L⁻¹`, `L⁻ᵀ` (on each column of `Cᵀ` and on `f̃`) and `M̃x`, all O(bodies)
//! per column here.

use faer::MatMut;
use faer::reborrow::{Reborrow, ReborrowMut};
use hagfish_solver::{FactoredMass, MassOperator};

use crate::factor::TreeFactor;

impl FactoredMass for TreeFactor {
    /// `x ← L⁻¹x` column by column (the leaf-to-root pass).
    fn solve_lower(&self, mut x: MatMut<'_, f64>) {
        for j in 0..x.ncols() {
            for_column(x.rb_mut().col_mut(j), |c| self.solve_lower_column(c));
        }
    }

    /// `x ← L⁻ᵀx` column by column (the root-to-leaf pass).
    fn solve_upper(&self, mut x: MatMut<'_, f64>) {
        for j in 0..x.ncols() {
            for_column(x.rb_mut().col_mut(j), |c| self.solve_upper_column(c));
        }
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
