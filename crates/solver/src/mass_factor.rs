//! Reverse-order Cholesky factor of the effective mass matrix, M̃ = U Uᵀ with U upper
//! triangular.
//!
//! Factored once per solve and reused by every path: M̃⁻¹x = U⁻ᵀ(U⁻¹x). U is the Cholesky
//! factor of M̃ with its DOFs in reverse order: with P the reversal permutation,
//! PM̃P = R Rᵀ (R lower triangular, faer's Cholesky) gives M̃ = (PRP)(PRP)ᵀ and U = PRP.
//!
//! Why reversed: in reduced coordinates rooted at the head, a constraint row on body k has
//! nonzeros only in the DOFs of joints 0..k (its ancestors), i.e. trailing zeros. Back
//! substitution with an upper-triangular U keeps them, U⁻¹c vanishes wherever c does from
//! its last nonzero e on, and costs e²/2 instead of n²/2 (forward substitution with a lower
//! L fills them). See [`FactoredMass::lower_support`].
//!
//! Only R is stored (U = PRP is applied by reversing the vectors around R's solves); it and
//! the faer scratch are owned here and only reallocated when n grows.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{
    LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};

use crate::error::SolverError;
use crate::mass_operator::FactoredMass;

/// Rows per block of [`MassFactor::solve_lower_supported`]: a column joins the blocked solve
/// at the first block that reaches its support, so at most this many zero rows are processed.
const BLOCK: usize = 32;

/// Owned factor of M̃ = U Uᵀ, kept as R = PUP, the lower-triangular Cholesky factor of PM̃P
/// (lower triangle of `reversed`; the strict upper part is junk).
pub(crate) struct MassFactor {
    reversed: Mat<f64>,
    scratch: MemBuffer,
    scratch_dofs: usize,
}

impl core::fmt::Debug for MassFactor {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MassFactor")
            .field("reversed", &self.reversed)
            .field("scratch_dofs", &self.scratch_dofs)
            .finish_non_exhaustive()
    }
}

impl MassFactor {
    /// An empty factor; buffers are sized by the first [`MassFactor::factor`].
    pub(crate) fn new() -> Self {
        Self {
            reversed: Mat::zeros(0, 0),
            scratch: MemBuffer::new(cholesky_in_place_scratch::<f64>(
                0,
                Par::Seq,
                Default::default(),
            )),
            scratch_dofs: 0,
        }
    }

    /// Computes R with PM̃P = R Rᵀ from the upper triangle of `mass` (so M̃ = U Uᵀ, U = PRP). A
    /// non-positive pivot is reported at its DOF in M̃'s own order.
    pub(crate) fn factor(&mut self, mass: MatRef<'_, f64>) -> Result<(), SolverError> {
        let n = mass.nrows();
        if n > self.scratch_dofs {
            self.scratch =
                MemBuffer::new(cholesky_in_place_scratch::<f64>(n, Par::Seq, Default::default()));
            self.scratch_dofs = n;
        }
        self.reversed.resize_with(n, n, |_, _| 0.0);
        // (PM̃P)ᵢⱼ = M̃_{n−1−i, n−1−j}: column j of R's lower triangle (rows j..n) is M̃'s
        // column n−1−j above the diagonal (rows n−1−j down to 0), read backwards.
        for j in 0..n {
            let source = mass.col(n - 1 - j).subrows(0, n - j).reverse_rows();
            self.reversed.as_mut().col_mut(j).subrows_mut(j, n - j).copy_from(source);
        }
        cholesky_in_place(
            self.reversed.as_mut(),
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        )
        .map(|_| ())
        .map_err(|err| match err {
            faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                SolverError::NotPositiveDefinite { pivot: n - 1 - index }
            }
        })
    }
}

/// Reverses the order of x's rows (x ← Px).
fn reverse_rows(mut x: MatMut<'_, f64>) {
    let n = x.nrows();
    for j in 0..x.ncols() {
        let mut column = x.rb_mut().col_mut(j);
        for i in 0..n / 2 {
            let (a, b) = (column[i], column[n - 1 - i]);
            column[i] = b;
            column[n - 1 - i] = a;
        }
    }
}

impl FactoredMass for MassFactor {
    /// x ← U⁻¹x = P R⁻¹ P x for every column of x (back substitution in M̃'s order).
    fn solve_lower(&self, mut x: MatMut<'_, f64>) {
        reverse_rows(x.rb_mut());
        solve_lower_triangular_in_place(self.reversed.as_ref(), x.rb_mut(), Par::Seq);
        reverse_rows(x);
    }

    /// x ← U⁻ᵀx = P R⁻ᵀ P x for every column of x.
    fn solve_upper(&self, mut x: MatMut<'_, f64>) {
        reverse_rows(x.rb_mut());
        solve_upper_triangular_in_place(self.reversed.transpose(), x.rb_mut(), Par::Seq);
        reverse_rows(x);
    }

    /// U is upper triangular: U⁻¹x vanishes wherever x does from `end` on.
    fn lower_support(&self, end: usize) -> Option<usize> {
        Some(end)
    }

    /// Blocked forward substitution with R on Px, whose column j has n − supportⱼ leading
    /// zeros: row blocks of [`BLOCK`] from the first nonzero row of any column down; a block
    /// solves its diagonal triangle for the columns that reach it (a prefix, by the order of
    /// `support`) and updates the rows below them by one product.
    fn solve_lower_supported(&self, mut x: MatMut<'_, f64>, support: &[usize]) {
        let n = x.nrows();
        let r = self.reversed.as_ref();
        reverse_rows(x.rb_mut());
        let mut start = n - support.first().copied().unwrap_or(0);
        while start < n {
            let end = (start + BLOCK).min(n);
            let active = support.partition_point(|&e| n - e < end);
            let (block, below) = x.rb_mut().subcols_mut(0, active).split_at_row_mut(end);
            let mut block = block.subrows_mut(start, end - start);
            let diagonal = r.submatrix(start, start, end - start, end - start);
            solve_lower_triangular_in_place(diagonal, block.rb_mut(), Par::Seq);
            let left = r.submatrix(end, start, n - end, end - start);
            matmul(below, Accum::Add, left, block.rb(), -1.0, Par::Seq);
            start = end;
        }
        reverse_rows(x);
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use faer::linalg::solvers::Solve;
    use faer::{Side, mat};
    use proptest::prelude::*;

    use super::*;
    use crate::linalg::column_mut;

    /// SplitMix64 in [−1, 1): a deterministic stream from a proptest seed.
    pub(crate) fn stream(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            2.0 * ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 - 1.0
        }
    }

    /// A random SPD n × n matrix S(AᵀA/n + 0.1 I)S with S's diagonal spanning 1e-2 … 1e2
    /// (condition up to ~1e5, like the hagfish's M̃).
    pub(crate) fn random_spd(n: usize, next: &mut impl FnMut() -> f64) -> Mat<f64> {
        let a = Mat::from_fn(n, n, |_, _| next());
        let scale: Vec<f64> = (0..n).map(|_| 10f64.powf(2.0 * next())).collect();
        let b = a.transpose() * &a;
        Mat::from_fn(n, n, |i, j| {
            let bij = b[(i, j)] / n as f64 + if i == j { 0.1 } else { 0.0 };
            scale[i] * bij * scale[j]
        })
    }

    /// Largest |aᵢⱼ − bᵢⱼ| relative to 1 + max|bᵢⱼ|.
    pub(crate) fn relative_gap(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> f64 {
        (a - b).norm_max() / (1.0 + b.norm_max())
    }

    fn reverse_factor_matches_faer(n: usize, columns: usize, seed: u64) -> Result<(), String> {
        let mut next = stream(seed);
        let mass = random_spd(n, &mut next);
        let rhs = Mat::from_fn(n, columns, |_, _| next());
        let mut factor = MassFactor::new();
        factor.factor(mass.as_ref()).map_err(|e| e.to_string())?;
        let llt = mass.llt(Side::Lower).map_err(|e| format!("{e:?}"))?;
        // M̃⁻¹B through U⁻ᵀU⁻¹ against faer's L⁻ᵀL⁻¹.
        let mut ours = rhs.clone();
        factor.solve_lower(ours.as_mut());
        // Bᵀ M̃⁻¹ B = (U⁻¹B)ᵀ(U⁻¹B) for any square root of M̃.
        let gram = ours.transpose() * &ours;
        factor.solve_upper(ours.as_mut());
        let reference = llt.solve(&rhs);
        let gap = relative_gap(ours.as_ref(), reference.as_ref());
        if gap > 1e-8 {
            return Err(format!("M̃⁻¹B differs by {gap:e}"));
        }
        let gap = relative_gap(gram.as_ref(), (rhs.transpose() * &reference).as_ref());
        if gap > 1e-8 {
            return Err(format!("BᵀM̃⁻¹B differs by {gap:e}"));
        }
        Ok(())
    }

    fn supported_solve_matches_full_solve(
        n: usize,
        columns: usize,
        seed: u64,
    ) -> Result<(), String> {
        let mut next = stream(seed);
        let mass = random_spd(n, &mut next);
        let mut support: Vec<usize> = (0..columns)
            .map(|_| ((next() + 1.0) * 0.5 * (n + 1) as f64) as usize % (n + 1))
            .collect();
        support.sort_unstable_by(|a, b| b.cmp(a));
        let rhs = Mat::from_fn(n, columns, |i, j| if i < support[j] { next() } else { 0.0 });
        let mut factor = MassFactor::new();
        factor.factor(mass.as_ref()).map_err(|e| e.to_string())?;
        let mut full = rhs.clone();
        factor.solve_lower(full.as_mut());
        let mut supported = rhs;
        factor.solve_lower_supported(supported.as_mut(), &support);
        for (j, &end) in support.iter().enumerate() {
            if let Some(i) = (end..n).find(|&i| full[(i, j)] != 0.0 || supported[(i, j)] != 0.0) {
                return Err(format!("column {j} (support {end}) nonzero at {i}"));
            }
        }
        let gap = relative_gap(supported.as_ref(), full.as_ref());
        if gap > 1e-12 {
            return Err(format!("supported solve differs by {gap:e}"));
        }
        Ok(())
    }

    proptest! {
        #[test]
        fn reverse_factor_agrees_with_faer_cholesky(
            n in 1usize..=60, columns in 1usize..=8, seed in any::<u64>()
        ) {
            reverse_factor_matches_faer(n, columns, seed).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn supported_solve_keeps_zeros_and_agrees_with_full_solve(
            n in 1usize..=80, columns in 0usize..=20, seed in any::<u64>()
        ) {
            supported_solve_matches_full_solve(n, columns, seed).map_err(TestCaseError::fail)?;
        }
    }

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
        // Eliminated from the last DOF: pivot 1 − 2²/1 < 0 at DOF 0.
        let mass = mat![[1.0, 2.0], [2.0, 1.0]];
        let mut factor = MassFactor::new();
        assert_eq!(
            factor.factor(mass.as_ref()),
            Err(SolverError::NotPositiveDefinite { pivot: 0 })
        );
    }
}
