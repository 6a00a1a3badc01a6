//! The contact-space (dual) operator of the velocity problem.
//!
//! With M̃ = L Lᵀ, Y = L⁻¹Cᵀ (n × m) and z = L⁻¹f̃:
//!
//! - W = C M̃⁻¹ Cᵀ + E = YᵀY + E (m × m, positive semidefinite; E the diagonal of the rows'
//!   compliances εᵢ, zero but for compliant rows; singular when hard rows are duplicated),
//! - q_free = M̃⁻¹f̃ = L⁻ᵀz, and r = b − C q_free = b − Yᵀz,
//! - for any λ, q̇(λ) = M̃⁻¹(f̃ + Cᵀλ) = L⁻ᵀ(z + Yλ), and the row residuals are
//!   Cq̇(λ) + Eλ − b = Wλ − r.
//!
//! Substituting q̇(λ) into the Lagrangian gives the dual QP
//! min ½λᵀWλ − λᵀr over the box (λ free on equalities, λ ≥ 0 on inequalities,
//! 0 ≤ λ ≤ weight on soft rows), whose gradient Wλ − r is exactly the vector of row
//! residuals: stationarity of the primal holds by construction, and the box QP's optimality
//! conditions are primal feasibility and complementarity.
//!
//! W is not regularised beyond the compliant rows' own εᵢ: duplicated or degenerate hard rows
//! make it singular, and the active-set method (`active_set.rs`) keeps the rows it factors
//! linearly independent instead.
//!
//! W is never formed: with rows made of bases (`reduced_rows.rs`: a friction pyramid's edges
//! over a contact's three bases) W = E W_R Eᵀ + E_c, and only W_R = Y_RᵀY_R of the p reduced
//! columns is kept (with the compliances of rows of their own on its diagonal); the active
//! set reads W's entries and Wλ through it (`dual_matrix.rs`). A knot pulled tight holds
//! ≈ 600 contacts of 8 rows: m = 4800 rows of 1800 reduced columns, a W 7× larger than W_R.
//!
//! Trailing zeros: a row cᵢ vanishing from entry e on (a contact on body k in reduced
//! coordinates rooted at the head: e = the end of the DOFs of joints 0..k) gives a column
//! L⁻¹cᵢ that vanishes from some eᵢ ≥ e on when the factor keeps trailing zeros
//! ([`FactoredMass::lower_support`]: eᵢ = e for the dense upper-triangular factor, the end
//! of joint k's DOFs for the tree factor). Then Y's column i costs eᵢ²/2 instead of n²/2
//! (dense) or the bodies 0..=k instead of all (tree), and Wᵢⱼ = Σ_{k < min(eᵢ, eⱼ)} YₖᵢYₖⱼ
//! skips the zero tails. Other factors use eᵢ = n.
//!
//! Ranges between the rows' breaks: where no row has a contact point (or a joint of its own)
//! in a run of a chain's joints, every column of Y_R there lies in a space of six vectors
//! ([`FactoredMass::wrench_span`]), and W_R is formed from its coordinates in that space
//! instead of the range's rows (`compressed_spans.rs`): the trunk between a knot and the
//! head, and the loop between a crossing's two strands, each become six rows of the product.

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};

use crate::error::SolverError;
use crate::linalg::{axpy, column, column_mut, dot, try_capacity, try_matrix_capacity};
use crate::mass_operator::FactoredMass;
use crate::problem::Problem;
use crate::reduced_rows::ReducedRows;

mod compressed_spans;
mod dual_matrix;
mod gram;
mod row_products;

use compressed_spans::CompressedSpans;
use gram::{form_w, mirror_upper};

pub(crate) use dual_matrix::ReducedScratch;

/// Columns of Y solved between two polls of the stop flag (a multiple of the tree factor's
/// four-column batches, so that the columns are solved as in one call).
const Y_CHUNK: usize = 64;

/// Entries of Y a block of W may read (its rows used × its columns) before its rows are
/// formed in chunks of [`gram::W_BLOCK`] with a poll of the stop flag between them: 2²⁴ (128 MiB),
/// far beyond the knotted states of a few hundred bodies, reached on tens of thousands, where
/// one block would otherwise run unpolled for a second.
const W_POLLED_ENTRIES: usize = 1 << 24;

/// Y_R, W_R, z, r and b of one solve (sizes n × p, p × p, n, m, m), the support eᵢ of the
/// rows' columns of Y = Y_R Eᵀ (entries eᵢ.. of column i are zero), the reduced columns
/// (`reduced_rows.rs`; the rows themselves when no row is a combination), numbered by
/// decreasing support, and their supports; `order` and `position` are the build's scratch.
#[derive(Debug)]
pub(crate) struct ContactSpace {
    /// Y_R = L⁻¹ of the reduced columns, in their order (Y itself without combinations).
    y: Mat<f64>,
    support: Vec<usize>,
    reduced: ReducedRows,
    /// The reduced columns' supports, decreasing.
    column_support: Vec<usize>,
    order: Vec<usize>,
    position: Vec<usize>,
    /// W_R = Y_RᵀY_R, both triangles, with εᵢ on the diagonal of a row of its own (then W_R's
    /// entry is W's).
    w: Mat<f64>,
    /// b_own − Y_Rᵀz (p; [`ContactSpace::update_force`]).
    reduced_r: Vec<f64>,
    compliance: Vec<f64>,
    z: Vec<f64>,
    r: Vec<f64>,
    b: Vec<f64>,
    /// Y_R with the DOF ranges between the rows' breaks compressed, W_R's input where any is
    /// (`compressed_spans.rs`).
    spans: CompressedSpans,
    /// The DOFs and rows Y_R and W_R have room for.
    reserved: (usize, usize),
}

impl ContactSpace {
    /// Empty buffers, sized by the first build.
    pub(crate) fn new() -> Self {
        Self {
            y: Mat::zeros(0, 0),
            support: Vec::new(),
            reduced: ReducedRows::default(),
            column_support: Vec::new(),
            order: Vec::new(),
            position: Vec::new(),
            w: Mat::zeros(0, 0),
            reduced_r: Vec::new(),
            compliance: Vec::new(),
            z: Vec::new(),
            r: Vec::new(),
            b: Vec::new(),
            spans: CompressedSpans::new(),
            reserved: (0, 0),
        }
    }

    /// Reserves room for problems of up to `dofs` velocities and `rows` rows.
    ///
    /// # Errors
    /// [`SolverError::Allocation`] if a buffer cannot be allocated.
    pub(crate) fn try_reserve(&mut self, dofs: usize, rows: usize) -> Result<(), SolverError> {
        self.try_reserve_matrices(dofs, rows)?;
        self.spans.try_reserve(dofs, rows)?;
        self.reduced.try_reserve(rows)?;
        let indices =
            [&mut self.support, &mut self.column_support, &mut self.order, &mut self.position];
        for buffer in indices {
            try_capacity(buffer, rows, "a contact-space index")?;
        }
        for buffer in [&mut self.compliance, &mut self.r, &mut self.b, &mut self.reduced_r] {
            try_capacity(buffer, rows, "a contact-space row vector")?;
        }
        try_capacity(&mut self.z, dofs, "z = L⁻¹f̃")
    }

    /// Room for Y_R (`dofs` × `rows`) and W_R (`rows` × `rows`: there are at most as many
    /// reduced columns as rows); nothing is allocated when
    /// they are that large already. Every build rewrites them whole, so they grow afresh (no
    /// copy of the old values) and by a quarter of their rows at least: rows added step by
    /// step (a knot forming on 100 000 bodies adds ≈ 100 a step to ≈ 1000) would otherwise
    /// copy gigabytes each step, unpolled by the stop flag.
    fn try_reserve_matrices(&mut self, dofs: usize, rows: usize) -> Result<(), SolverError> {
        let (reserved_dofs, reserved_rows) = self.reserved;
        if dofs <= reserved_dofs && rows <= reserved_rows {
            return Ok(());
        }
        let (dofs, rows) = (dofs.max(reserved_dofs), rows.max(reserved_rows + reserved_rows / 4));
        let matrices = [
            (&mut self.y, dofs, "Y_R = L⁻¹ of the reduced columns"),
            (&mut self.w, rows, "W_R = Y_RᵀY_R"),
        ];
        for (matrix, height, what) in matrices {
            *matrix = Mat::zeros(0, 0);
            try_matrix_capacity(matrix, height, rows, what)?;
        }
        self.reserved = (dofs, rows);
        Ok(())
    }

    /// Forms Y_R, W_R (module docs), the rows' supports, z = L⁻¹f̃ and r = b − Yᵀz for
    /// `problem`, with `factor` holding a factor of its M̃ (M̃ = L Lᵀ); skips the rows'
    /// trailing zeros when the factor keeps them (module docs).
    ///
    /// # Errors
    /// [`SolverError::Allocation`] if the matrices must grow and cannot (the contact space
    /// then holds no problem).
    pub(crate) fn build(
        &mut self,
        factor: &dyn FactoredMass,
        problem: &Problem<'_>,
    ) -> Result<(), SolverError> {
        let rows = problem.rows();
        let (n, m) = (problem.dofs(), rows.len());
        self.reduced.reduce(rows);
        let p = self.reduced.len();
        self.try_reserve_matrices(n, m.max(p))?;
        self.spans.try_reserve(n, m.max(p))?;
        let reduced = &self.reduced;
        self.column_support.clear();
        self.column_support.extend((0..p).map(|j| {
            let column = reduced.column(rows, j);
            let end = column.iter().rposition(|&c| c != 0.0).map_or(0, |last| last + 1);
            factor.lower_support(end).unwrap_or(n)
        }));
        // The columns by decreasing support (ties by their order), so that W_R's blocks skip
        // the zero tails.
        self.order.clear();
        self.order.extend(0..p);
        let support = &self.column_support;
        self.order.sort_unstable_by_key(|&j| (core::cmp::Reverse(support[j]), j));
        self.reduced.reorder(&self.order, &mut self.position);
        self.position.clear();
        self.position.extend(self.order.iter().map(|&j| self.column_support[j]));
        std::mem::swap(&mut self.column_support, &mut self.position);
        self.y.resize_with(n, p, |_, _| 0.0);
        for k in 0..p {
            self.y.col_as_slice_mut(k).copy_from_slice(self.reduced.column(rows, k));
        }
        for first in (0..p).step_by(Y_CHUNK) {
            problem.check_stop()?;
            let count = Y_CHUNK.min(p - first);
            let chunk = self.y.as_mut().submatrix_mut(0, first, n, count);
            factor.solve_lower_supported(chunk, &self.column_support[first..first + count]);
        }
        problem.check_stop()?;
        let (y, support) = (self.y.as_ref(), &self.column_support[..]);
        let compressed = self.spans.compress(factor, (rows, &self.reduced), y, support);
        let input = if compressed { self.spans.compressed() } else { (y, support) };
        form_w(&mut self.w, input, W_POLLED_ENTRIES, problem)?;
        if compressed && !self.spans.within_bound(self.w.as_ref()) {
            self.spans.discard();
            form_w(&mut self.w, (y, support), W_POLLED_ENTRIES, problem)?;
        }
        mirror_upper(&mut self.w);
        self.compliance.clear();
        self.compliance.extend(rows.kinds().iter().map(|kind| kind.compliance()));
        for (i, &compliance) in self.compliance.iter().enumerate() {
            if let Some(column) = self.reduced.own_column(i).filter(|_| compliance != 0.0) {
                self.w[(column, column)] += compliance;
            }
        }
        let (reduced, column_support) = (&self.reduced, &self.column_support);
        self.support.clear();
        self.support.extend(
            (0..m).map(|i| {
                reduced.terms(i).iter().map(|&(j, _)| column_support[j]).max().unwrap_or(0)
            }),
        );
        self.update_force(factor, problem);
        Ok(())
    }

    /// Recomputes z = L⁻¹f̃ and r = b − Yᵀz for a new f̃ and new right-hand sides b, keeping Y
    /// and W: for a problem whose M̃ and row coefficients are those of the last
    /// [`build`](Self::build). Through the reduced columns: t = b_own − Y_Rᵀz (b of a row of
    /// its own, 0 for a base), then rᵢ = t of a row of its own, bᵢ + Σ_t w_t t_{j_t} of a
    /// combination (without combinations the product of before, bit for bit).
    pub(crate) fn update_force(&mut self, factor: &dyn FactoredMass, problem: &Problem<'_>) {
        self.b.clear();
        self.b.extend_from_slice(problem.rhs());
        self.z.clear();
        self.z.extend_from_slice(problem.force());
        factor.solve_lower(column_mut(&mut self.z));
        let (reduced, b) = (&self.reduced, &self.b);
        self.reduced_r.clear();
        self.reduced_r.extend((0..reduced.len()).map(|j| reduced.own_row(j).map_or(0.0, |i| b[i])));
        let (t, z) = (column_mut(&mut self.reduced_r), column(&self.z));
        matmul(t, Accum::Add, self.y.transpose(), z, -1.0, Par::Seq);
        self.r.clear();
        self.r.extend(b.iter().enumerate().map(|(i, &bi)| match reduced.own_column(i) {
            Some(j) => self.reduced_r[j],
            None => bi + reduced.terms(i).iter().map(|&(j, w)| w * self.reduced_r[j]).sum::<f64>(),
        }));
    }

    /// Rows of Y_R that the last build's W_R left out (`compressed_spans.rs`).
    pub(crate) fn gram_rows_saved(&self) -> usize {
        self.spans.rows_saved()
    }

    /// The rows' compliances εᵢ (the diagonal E in W; 0 but for compliant rows).
    pub(crate) fn compliance(&self) -> &[f64] {
        &self.compliance
    }

    /// Number of rows m of the last build.
    pub(crate) fn rows(&self) -> usize {
        self.b.len()
    }

    /// Number of DOFs n.
    pub(crate) fn dofs(&self) -> usize {
        self.z.len()
    }

    /// The supports eᵢ (m): row i and Y's column i vanish from entry eᵢ on.
    pub(crate) fn supports(&self) -> &[usize] {
        &self.support
    }

    /// Reduced column j of Y_R up to its support.
    fn reduced_column(&self, j: usize) -> &[f64] {
        &self.y.col_as_slice(j)[..self.column_support[j]]
    }

    /// yᵢᵀx with yᵢ = L⁻¹cᵢ, column i of Y = Y_R Eᵀ: Σ_t w_t Y_R[:, j_t]ᵀx.
    pub(crate) fn y_dot(&self, i: usize, x: &[f64]) -> f64 {
        match self.reduced.own_column(i) {
            Some(j) => dot(self.reduced_column(j), x),
            None => {
                let terms = self.reduced.terms(i).iter();
                terms.map(|&(j, w)| w * dot(self.reduced_column(j), x)).sum()
            }
        }
    }

    /// x ← x + a·yᵢ, yᵢ = L⁻¹cᵢ as in [`ContactSpace::y_dot`].
    pub(crate) fn y_axpy(&self, i: usize, a: f64, x: &mut [f64]) {
        for &(j, w) in self.reduced.terms(i) {
            axpy(a * w, self.reduced_column(j), x);
        }
    }

    /// r = b − C M̃⁻¹f̃ (m).
    pub(crate) fn r(&self) -> &[f64] {
        &self.r
    }

    /// b, the rows' right-hand sides (m): exact data, unlike r, whose Yᵀz term carries the
    /// rounding of large cancelling products when M̃ is ill-conditioned.
    pub(crate) fn b(&self) -> &[f64] {
        &self.b
    }

    /// out ← z + Yλ = z + Y_R Eᵀλ = Lᵀq̇(λ), whose norm is ‖q̇(λ)‖_M (`scratch` holds Eᵀλ).
    pub(crate) fn lift(&self, lambda: &[f64], scratch: &mut ReducedScratch, out: &mut [f64]) {
        let folded = self.fold(lambda, scratch);
        out.copy_from_slice(&self.z);
        matmul(column_mut(out), Accum::Add, self.y.as_ref(), column(folded), 1.0, Par::Seq);
    }

    /// q̇ ← M̃⁻¹(f̃ + Cᵀλ) = L⁻ᵀ(z + Yλ).
    pub(crate) fn recover(
        &self,
        factor: &dyn FactoredMass,
        lambda: &[f64],
        scratch: &mut ReducedScratch,
        qdot: &mut [f64],
    ) {
        self.lift(lambda, scratch, qdot);
        factor.solve_upper(column_mut(qdot));
    }
}

#[cfg(test)]
mod tests {
    use faer::linalg::solvers::Llt;
    use faer::{MatMut, Side};
    use proptest::prelude::*;

    use super::*;
    use crate::linalg::Entries;
    use crate::mass_factor::MassFactor;
    use crate::mass_factor::tests::{random_spd, relative_gap, stream};
    use crate::rows::{RowKind, RowSource, RowTag, Rows};

    /// faer's lower Cholesky factor M̃ = LLᵀ: a factor that does not keep trailing zeros (the
    /// default path of [`FactoredMass::solve_lower_supported`]).
    #[derive(Debug)]
    struct LowerFactor(Llt<f64>);

    impl FactoredMass for LowerFactor {
        fn solve_lower(&self, x: MatMut<'_, f64>) {
            let l = self.0.L();
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, x, Par::Seq);
        }

        fn solve_upper(&self, x: MatMut<'_, f64>) {
            let lt = self.0.L().transpose();
            faer::linalg::triangular_solve::solve_upper_triangular_in_place(lt, x, Par::Seq);
        }
    }

    /// Rows with random trailing zeros (and a few all-zero and full rows) give the same W, r and
    /// Yλ with the reverse factor (tails skipped) as with faer's LLᵀ (tails filled).
    fn tails_are_exact(n: usize, m: usize, seed: u64) -> Result<(), String> {
        let mut next = stream(seed);
        let mass = random_spd(n, &mut next);
        let force: Vec<f64> = (0..n).map(|_| next()).collect();
        let mut rows = Rows::new(n);
        for _ in 0..m {
            let end = ((next() + 1.0) * 0.5 * (n + 1) as f64) as usize % (n + 1);
            let row =
                rows.push_zeroed(RowKind::Inequality, RowSource::new(RowTag::new(3), 0), next());
            row[..end].iter_mut().for_each(|c| *c = next());
        }
        let problem = Problem::new(mass.as_ref(), &force, &rows).map_err(|e| e.to_string())?;
        let mut reverse = MassFactor::new();
        reverse.factor(mass.as_ref()).map_err(|e| e.to_string())?;
        let lower = LowerFactor(mass.llt(Side::Lower).map_err(|e| format!("{e:?}"))?);
        let (mut tailed, mut filled) = (ContactSpace::new(), ContactSpace::new());
        tailed.build(&reverse, &problem).expect("room for Y and W");
        filled.build(&lower, &problem).expect("room for Y and W");
        let lambda: Vec<f64> = (0..m).map(|_| next()).collect();
        agree((&tailed, &reverse), (&filled, &lower), &lambda, n)
    }

    /// Whether two contact spaces built from the same problem of `dofs` DOFs agree: W and r
    /// within 10⁻¹⁰ and the velocity recovered from λ (each with its factor) within 10⁻⁸,
    /// relative; the first one's W exactly symmetric (the active set reads either triangle),
    /// its gradient Wλ − r the second one's W times λ less r within 10⁻¹⁰ of the terms' size,
    /// and its magnitude no smaller than that size; or how they do not.
    fn agree(
        (a, a_factor): (&ContactSpace, &dyn FactoredMass),
        (b, b_factor): (&ContactSpace, &dyn FactoredMass),
        lambda: &[f64],
        dofs: usize,
    ) -> Result<(), String> {
        let m = lambda.len();
        let formed = |space: &ContactSpace| Mat::<f64>::from_fn(m, m, |i, j| space.entry(i, j));
        let (w_a, w_b) = (formed(a), formed(b));
        let (mut qa, mut qb) = (vec![0.0; dofs], vec![0.0; dofs]);
        a.recover(a_factor, lambda, &mut ReducedScratch::default(), &mut qa);
        b.recover(b_factor, lambda, &mut ReducedScratch::default(), &mut qb);
        let (w, r) =
            (relative_gap(w_a.as_ref(), w_b.as_ref()), relative_gap(column(a.r()), column(b.r())));
        let qdot = relative_gap(column(&qa), column(&qb));
        let symmetric = (0..m).all(|i| (0..m).all(|j| w_a[(i, j)] == w_a[(j, i)]));
        // The gradient through W_R against the formed W's product, term by term.
        let (mut gradient, mut magnitude) = (vec![0.0; m], vec![0.0; m]);
        a.gradient(lambda, &mut ReducedScratch::default(), &mut gradient, &mut magnitude);
        let mut worst = 0.0_f64;
        for (i, &magnitude) in magnitude.iter().enumerate() {
            let terms = (0..m).map(|j| w_b[(i, j)] * lambda[j]);
            let (product, size) =
                terms.fold((0.0, 0.0), |(sum, size), t| (sum + t, size + t.abs()));
            let expected = product - b.r()[i];
            let scale = 1.0 + b.r()[i].abs() + size;
            worst = worst.max((gradient[i] - expected).abs() / scale);
            if magnitude < (1.0 - 1e-12) * (b.r()[i].abs() + size) {
                return Err(format!(
                    "row {i}: magnitude {} below Σ|Wλ| + |r| = {}",
                    magnitude,
                    b.r()[i].abs() + size
                ));
            }
        }
        if w > 1e-10 || r > 1e-10 || qdot > 1e-8 || !symmetric || worst > 1e-10 {
            return Err(format!(
                "W {w:e}, r {r:e}, q̇ {qdot:e}, symmetric {symmetric}, Wλ − r {worst:e}"
            ));
        }
        Ok(())
    }

    /// W formed in polled row chunks (as for a huge body) equals W formed a block at once, to
    /// rounding; and Y solved in chunks of [`Y_CHUNK`] columns, with more rows than one chunk,
    /// is Y solved at once, bit for bit.
    #[test]
    fn w_in_polled_chunks_and_y_in_column_chunks_are_the_same_products() {
        let (n, m) = (40, 2 * Y_CHUNK + 5);
        let mut next = stream(7);
        let mass = random_spd(n, &mut next);
        let force: Vec<f64> = (0..n).map(|_| next()).collect();
        let mut rows = Rows::new(n);
        for _ in 0..m {
            let row =
                rows.push_zeroed(RowKind::Inequality, RowSource::new(RowTag::new(3), 0), next());
            row.iter_mut().for_each(|c| *c = next());
        }
        let problem = Problem::new(mass.as_ref(), &force, &rows).expect("a problem");
        let mut reverse = MassFactor::new();
        reverse.factor(mass.as_ref()).expect("SPD");
        let mut space = ContactSpace::new();
        space.build(&reverse, &problem).expect("room for Y and W");
        let mut whole = Mat::<f64>::zeros(n, m);
        for k in 0..m {
            whole.col_as_slice_mut(k).copy_from_slice(space.reduced.column(&rows, k));
        }
        reverse.solve_lower_supported(whole.as_mut(), &space.column_support);
        assert!(whole == space.y, "Y solved in chunks of {Y_CHUNK} columns");
        let at_once = space.w.clone();
        let mut polled = Mat::zeros(0, 0);
        form_w(&mut polled, (space.y.as_ref(), &space.column_support), 0, &problem)
            .expect("not stopped");
        let upper =
            |w: &Mat<f64>| Mat::<f64>::from_fn(m, m, |i, j| if i <= j { w[(i, j)] } else { 0.0 });
        let gap = relative_gap(upper(&polled).as_ref(), upper(&at_once).as_ref());
        assert!(gap < 1e-14, "W in polled chunks differs by {gap:e}");
    }

    /// Rows made of bases (`Rows::push_combination`: a pyramid's edges over a contact's three
    /// bases, with trailing zeros; some compliant, as rows of their own between contacts) give
    /// the W, r, Wλ − r, q̇(λ) and Cq̇ of the same rows written out, and an exactly symmetric W.
    fn combinations_are_their_rows(n: usize, contacts: usize, seed: u64) -> Result<(), String> {
        let mut next = stream(seed);
        let mass = random_spd(n, &mut next);
        let force: Vec<f64> = (0..n).map(|_| next()).collect();
        let (mut combined, mut own) = (Rows::new(n), Rows::new(n));
        let (source, inequality) = (RowSource::new(RowTag::new(3), 0), RowKind::Inequality);
        for contact in 0..contacts {
            let end = ((next() + 1.0) * 0.5 * (n + 1) as f64) as usize % (n + 1);
            let first = combined.push_bases();
            for base in combined.bases_mut(first) {
                base[..end].iter_mut().for_each(|c| *c = next());
            }
            // A row of its own between contacts, as a joint limit's (compliant, as a skin's,
            // every other time); and the first edge of every other contact compliant: εᵢ on
            // W_R's diagonal for a row of its own, on W's alone for a combination.
            let compliant = RowKind::Compliant { compliance: 0.1 + next().abs() };
            if contact % 2 == 1 {
                let row: Vec<f64> = (0..n).map(|_| next()).collect();
                let (rhs, kind) = (next(), if contact % 4 == 3 { compliant } else { inequality });
                combined.push_zeroed(kind, source, rhs).copy_from_slice(&row);
                own.push_zeroed(kind, source, rhs).copy_from_slice(&row);
            }
            for edge in 0..8 {
                let (weights, rhs) = ([next(), next(), next()], next());
                let kind = if edge == 0 && contact % 2 == 0 { compliant } else { inequality };
                combined.push_combination(kind, source, rhs, (first, weights));
                let written = combined.coefficients_of(combined.len() - 1).to_vec();
                own.push_zeroed(kind, source, rhs).copy_from_slice(&written);
            }
        }
        let m = own.len();
        let mut reverse = MassFactor::new();
        reverse.factor(mass.as_ref()).map_err(|e| e.to_string())?;
        let (mut from_bases, mut from_rows) = (ContactSpace::new(), ContactSpace::new());
        let problem = Problem::new(mass.as_ref(), &force, &combined).map_err(|e| e.to_string())?;
        from_bases.build(&reverse, &problem).expect("room for Y and W");
        let problem = Problem::new(mass.as_ref(), &force, &own).map_err(|e| e.to_string())?;
        from_rows.build(&reverse, &problem).expect("room for Y and W");
        let lambda: Vec<f64> = (0..m).map(|_| next()).collect();
        agree((&from_bases, &reverse), (&from_rows, &reverse), &lambda, n)?;
        if from_bases.supports() != from_rows.supports() {
            return Err("the rows' supports differ".into());
        }
        // The rows' products with q̇ through the bases: the written rows' within 10⁻¹⁰ of
        // their size, and a size no smaller than theirs.
        let qdot: Vec<f64> = (0..n).map(|_| next()).collect();
        let (mut through_bases, mut written) = (Vec::new(), Vec::new());
        let scratch = &mut ReducedScratch::default();
        from_bases.row_products(&combined, &qdot, scratch, &mut through_bases);
        from_rows.row_products(&own, &qdot, scratch, &mut written);
        for (i, (&(product, size), &(expected, least))) in
            through_bases.iter().zip(&written).enumerate()
        {
            if (product - expected).abs() > 1e-10 * (1.0 + least) || size < (1.0 - 1e-12) * least {
                return Err(format!(
                    "row {i}: cᵀq̇ {product} (size {size}), rows {expected} ({least})"
                ));
            }
        }
        Ok(())
    }

    proptest! {
        #[test]
        fn rows_made_of_bases_are_the_rows_they_make(
            n in 1usize..=40, contacts in 0usize..=6, seed in any::<u64>()
        ) {
            combinations_are_their_rows(n, contacts, seed).map_err(TestCaseError::fail)?;
        }

        #[test]
        fn trailing_zeros_are_skipped_exactly(
            n in 1usize..=60, m in 0usize..=30, seed in any::<u64>()
        ) {
            tails_are_exact(n, m, seed).map_err(TestCaseError::fail)?;
        }
    }
}
