//! Cholesky factor of the effective mass matrix, M̃ = L Lᵀ.
//!
//! Factored once per solve and reused by every path: M̃⁻¹x = L⁻ᵀ(L⁻¹x). The factor and the
//! faer scratch are owned here and only reallocated when n grows.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{
    LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, MatMut, MatRef, Par};

use crate::error::SolverError;
use crate::mass_operator::FactoredMass;

/// Owned Cholesky factor L of M̃ (lower triangle of `factor`; the strict upper part is junk).
pub(crate) struct MassFactor {
    factor: Mat<f64>,
    scratch: MemBuffer,
    scratch_dofs: usize,
}

impl core::fmt::Debug for MassFactor {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MassFactor")
            .field("factor", &self.factor)
            .field("scratch_dofs", &self.scratch_dofs)
            .finish_non_exhaustive()
    }
}

impl MassFactor {
    /// An empty factor; buffers are sized by the first [`MassFactor::factor`].
    pub(crate) fn new() -> Self {
        Self {
            factor: Mat::zeros(0, 0),
            scratch: MemBuffer::new(cholesky_in_place_scratch::<f64>(
                0,
                Par::Seq,
                Default::default(),
            )),
            scratch_dofs: 0,
        }
    }

    /// Computes L with M̃ = L Lᵀ from the lower triangle of `mass`.
    pub(crate) fn factor(&mut self, mass: MatRef<'_, f64>) -> Result<(), SolverError> {
        let n = mass.nrows();
        if n > self.scratch_dofs {
            self.scratch =
                MemBuffer::new(cholesky_in_place_scratch::<f64>(n, Par::Seq, Default::default()));
            self.scratch_dofs = n;
        }
        self.factor.resize_with(n, n, |_, _| 0.0);
        self.factor.copy_from_triangular_lower(mass);
        cholesky_in_place(
            self.factor.as_mut(),
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        )
        .map(|_| ())
        .map_err(|err| match err {
            faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                SolverError::NotPositiveDefinite { pivot: index }
            }
        })
    }
}

impl FactoredMass for MassFactor {
    /// x ← L⁻¹x for every column of x (triangular solve with the Cholesky factor).
    fn solve_lower(&self, x: MatMut<'_, f64>) {
        solve_lower_triangular_in_place(self.factor.as_ref(), x, Par::Seq);
    }

    /// x ← L⁻ᵀx for every column of x.
    fn solve_upper(&self, x: MatMut<'_, f64>) {
        solve_upper_triangular_in_place(self.factor.transpose(), x, Par::Seq);
    }
}

#[cfg(test)]
mod tests {
    use faer::mat;

    use super::*;
    use crate::linalg::column_mut;

    #[test]
    fn solves_with_the_factor() -> Result<(), SolverError> {
        let mass = mat![[4.0, 2.0], [2.0, 3.0]];
        let mut factor = MassFactor::new();
        factor.factor(mass.as_ref())?;
        let mut x = [2.0, 1.0];
        factor.solve_lower(column_mut(&mut x));
        factor.solve_upper(column_mut(&mut x));
        // [[4, 2], [2, 3]] x = [2, 1]  →  x = [0.5, 0]
        assert!((x[0] - 0.5).abs() < 1e-15 && x[1].abs() < 1e-15);
        Ok(())
    }

    #[test]
    fn indefinite_mass_is_an_error() {
        let mass = mat![[1.0, 2.0], [2.0, 1.0]];
        let mut factor = MassFactor::new();
        assert_eq!(
            factor.factor(mass.as_ref()),
            Err(SolverError::NotPositiveDefinite { pivot: 1 })
        );
    }
}
