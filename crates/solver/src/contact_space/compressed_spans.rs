//! W_R = Y_RᵀY_R over fewer rows: the DOF ranges between the rows' breaks, each replaced by
//! its coordinates in an orthonormal basis of at most six vectors.
//!
//! On a range [s, e) of a chain's DOFs with no break of any reduced column strictly inside
//! (`wrench_breaks.rs`: no contact point, limit or head row in it), column j's coefficients
//! are s_aᵀF_j for one wrench F_j, and the leaf-to-root pass carries one six-vector through
//! the range: Y_R[s..e, j] = K x_j for the range's (e − s) × 6 matrix K
//! ([`FactoredMass::wrench_span`]). With Q an orthonormal basis of K's columns (k ≤ 6, by
//! classical Gram–Schmidt twice) and r_j = y_j − QQᵀy_j on the range,
//!
//! Y_R[s..e]ᵀ Y_R[s..e] = (QᵀY_R[s..e])ᵀ (QᵀY_R[s..e]) + RᵀR,
//!
//! so the range's e − s rows of the Gram product become k rows of coordinates QᵀY_R[s..e],
//! written in their place in a copy of Y_R (one product over contiguous rows: summing the
//! ranges' products block by block instead, without the copy, took the 9₁'s step from 0.77
//! to 0.86 of the plain product's, decision 0034). A knot's contacts pair points far apart along the body (the two strands of a
//! crossing), so most of a contact column's rows lie between contact points, and every column
//! of the knot runs through the trunk between the knot and the root: those rows are
//! compressed.
//!
//! When: a range of at least [`MIN_SPAN_DOFS`] DOFs that at least [`MIN_SPAN_COLUMNS`] columns
//! reach, and only when the ranges save a quarter of the product's work at least
//! ([`MIN_SAVED_FRACTION_INVERSE`]): the basis, the coordinates and their check read each
//! compressed row of Y_R twice and copies the rest, which costs what the product saves on few
//! columns.
//!
//! Checked, never trusted: the dropped RᵀR moves W_R by at most ‖rᵢ‖‖rⱼ‖, and every column's
//! ‖r_j‖² (summed over its ranges) must be at most 10⁻¹⁶‖y_j‖² ([`RESIDUAL_BOUND`] squared;
//! ‖y_j‖² = W_jj + ‖r_j‖², the whole column's), so that W_R moves by at most
//! 10⁻¹⁶‖yᵢ‖‖yⱼ‖, below the product's own rounding bound nε‖yᵢ‖‖yⱼ‖, whatever the cause: a
//! promise that left a break out fails it ([`CompressedSpans::within_bound`]), and the
//! contact space forms the plain product instead. (A range's own norm would be the wrong
//! scale: a contact normal's entries on the trunk are the small remainder of two points'
//! cancelling wrenches, ≈ 10⁻⁵ of the column, and carry the pass's rounding, ≈ 10⁻¹³ of it.)

use std::ops::Range;

use faer::linalg::matmul::matmul;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};

use crate::error::SolverError;
use crate::linalg::{dot, try_capacity, try_matrix_capacity};
use crate::mass_operator::FactoredMass;
use crate::reduced_rows::ReducedRows;
use crate::rows::Rows;
use crate::wrench_breaks::MAX_BREAKS;

/// The shortest range compressed (DOFs): eight bodies of three DOFs, four times the six rows
/// it becomes.
const MIN_SPAN_DOFS: usize = 24;

/// The fewest columns a range must carry into the product to be compressed. The product
/// spends p²/2 multiply-adds on each row of Y_R, the compression about four passes over the
/// row's p entries (its coordinates, their residual, the copy): on this machine they balance
/// near p ≈ 100, and the compression pays from about twice that (docs/decisions/0034: the
/// 1000-body knot's 152 columns compressed cost 270–460 µs and saved 300–390 µs of the
/// product).
const MIN_SPAN_COLUMNS: usize = 192;

/// The smallest share of the Gram product's work the compressed ranges must save, as its
/// inverse: a quarter.
const MIN_SAVED_FRACTION_INVERSE: usize = 4;

/// Largest residual ‖r_j‖ / ‖y_j‖ of a compressed column (module docs).
const RESIDUAL_BOUND: f64 = 1e-8;

/// Columns whose residual is formed at once.
const RESIDUAL_CHUNK: usize = 64;

/// A compressed range: its DOFs and the rank k of its basis (the rows it became).
#[derive(Debug, Clone)]
struct Span {
    dofs: Range<usize>,
    rank: usize,
}

/// The compressed ranges of one build, their coordinates and scratch.
#[derive(Debug)]
pub(crate) struct CompressedSpans {
    /// The ranges' ends: the reduced columns' breaks, sorted (scratch).
    positions: Vec<usize>,
    /// The ranges worth compressing and how many columns reach each (scratch).
    candidates: Vec<(Range<usize>, usize)>,
    /// The compressed ranges, by increasing DOFs.
    spans: Vec<Span>,
    /// Q of the range being compressed (n × 6).
    basis: Mat<f64>,
    /// y − QQᵀy of a chunk of columns (n × [`RESIDUAL_CHUNK`]).
    residual: Mat<f64>,
    /// Y_R with each compressed range's rows replaced by its coordinates QᵀY_R[range].
    y: Mat<f64>,
    /// Each column's support in `y`.
    support: Vec<usize>,
    /// ‖r_j‖² of each column, summed over the ranges.
    residuals: Vec<f64>,
    /// The DOFs and columns the buffers have room for.
    reserved: (usize, usize),
}

impl CompressedSpans {
    /// Empty buffers, sized by [`CompressedSpans::try_reserve`].
    pub(crate) fn new() -> Self {
        Self {
            positions: Vec::new(),
            candidates: Vec::new(),
            spans: Vec::new(),
            basis: Mat::zeros(0, 0),
            residual: Mat::zeros(0, 0),
            y: Mat::zeros(0, 0),
            support: Vec::new(),
            residuals: Vec::new(),
            reserved: (0, 0),
        }
    }

    /// Room for `columns` reduced columns over `dofs` DOFs (grows by a quarter at least, as
    /// Y_R does).
    pub(crate) fn try_reserve(&mut self, dofs: usize, columns: usize) -> Result<(), SolverError> {
        let (reserved_dofs, reserved_columns) = self.reserved;
        if dofs <= reserved_dofs && columns <= reserved_columns {
            return Ok(());
        }
        let (dofs, columns) =
            (dofs.max(reserved_dofs), columns.max(reserved_columns + reserved_columns / 4));
        let matrices = [
            (&mut self.basis, 6, "the compressed ranges' bases"),
            (&mut self.residual, RESIDUAL_CHUNK, "the compressed ranges' residuals"),
            (&mut self.y, columns, "Y_R with compressed ranges"),
        ];
        for (matrix, width, what) in matrices {
            *matrix = Mat::zeros(0, 0);
            try_matrix_capacity(matrix, dofs, width, what)?;
        }
        // Each range holds MIN_SPAN_DOFS DOFs at least.
        let ranges = dofs / MIN_SPAN_DOFS + 1;
        try_capacity(&mut self.positions, MAX_BREAKS * columns + 2, "the rows' breaks")?;
        try_capacity(&mut self.spans, ranges, "the compressed ranges")?;
        try_capacity(&mut self.candidates, ranges, "the compressed ranges")?;
        try_capacity(&mut self.residuals, columns, "the columns' residuals")?;
        try_capacity(&mut self.support, columns, "the compressed supports")?;
        self.reserved = (dofs, columns);
        Ok(())
    }

    /// Compresses the ranges of `y` (Y_R: its columns by decreasing `support`, those of
    /// `reduced` over `rows`) that the columns' breaks, `factor` and the cost allow (module
    /// docs); returns whether any was, and then [`CompressedSpans::compressed`] is the
    /// product's input. Needs room ([`CompressedSpans::try_reserve`]).
    pub(crate) fn compress(
        &mut self,
        factor: &dyn FactoredMass,
        (rows, reduced): (&Rows, &ReducedRows),
        y: MatRef<'_, f64>,
        support: &[usize],
    ) -> bool {
        self.spans.clear();
        let Some(&top) = support.first().filter(|_| support.len() >= MIN_SPAN_COLUMNS) else {
            return false;
        };
        self.collect_positions((rows, reduced), support, top);
        // The product's work, Σ over column pairs i ≤ j of min(eᵢ, eⱼ) = Σ_j (j + 1)·e_j
        // (supports decreasing), and what the candidates would save of it.
        let work: usize = support.iter().enumerate().map(|(j, &e)| (j + 1) * e).sum();
        let mut saved = 0;
        self.candidates.clear();
        for w in 1..self.positions.len() {
            let range = self.positions[w - 1]..self.positions[w];
            let alive = support.partition_point(|&e| e > range.start);
            if range.len() >= MIN_SPAN_DOFS && alive >= MIN_SPAN_COLUMNS {
                saved += (range.len() - 6) * alive * (alive + 1) / 2;
                self.candidates.push((range, alive));
            }
        }
        if self.candidates.is_empty() || saved < work / MIN_SAVED_FRACTION_INVERSE {
            return false;
        }
        let (n, p) = (y.nrows(), support.len());
        self.basis.resize_with(n, 6, |_, _| 0.0);
        self.residual.resize_with(n, RESIDUAL_CHUNK, |_, _| 0.0);
        self.y.resize_with(n, p, |_, _| 0.0);
        self.residuals.clear();
        self.residuals.resize(p, 0.0);
        // Y_R's rows below each compressed range, then its coordinates, then the rest.
        let (mut written, mut placed) = (0, 0);
        for c in 0..self.candidates.len() {
            let (range, alive) = self.candidates[c].clone();
            let count = range.start - placed;
            let rows_below = y.submatrix(placed, 0, count, p);
            self.y.as_mut().submatrix_mut(written, 0, count, p).copy_from(rows_below);
            (written, placed) = (written + count, range.start);
            if let Some(rank) = self.compress_range(factor, y, range.clone(), (alive, written)) {
                (written, placed) = (written + rank, range.end);
                self.spans.push(Span { dofs: range, rank });
            }
        }
        if self.spans.is_empty() {
            return false;
        }
        let count = top - placed;
        let rest = y.submatrix(placed, 0, count, p);
        self.y.as_mut().submatrix_mut(written, 0, count, p).copy_from(rest);
        self.support.clear();
        let spans = &self.spans;
        self.support.extend(support.iter().map(|&e| compressed_position(spans, e)));
        true
    }

    /// The sorted, distinct ends of the candidate ranges in `positions`: every break of a
    /// column below `top` above `floor`, the largest support of a column without breaks
    /// (written out below it), and `floor` and `top`.
    fn collect_positions(
        &mut self,
        (rows, reduced): (&Rows, &ReducedRows),
        support: &[usize],
        top: usize,
    ) {
        self.positions.clear();
        let mut floor = 0;
        for (j, &e) in support.iter().enumerate() {
            match reduced.breaks(rows, j) {
                Some(breaks) => self.positions.extend_from_slice(breaks.positions()),
                None => floor = floor.max(e),
            }
        }
        self.positions.retain(|&x| floor < x && x < top);
        self.positions.extend([floor, top]);
        self.positions.sort_unstable();
        self.positions.dedup();
    }

    /// Writes the coordinates QᵀY_R[range] of the first `alive` columns (those whose support
    /// reaches past the range's start) at row `at` of `self.y`, zeros for the others,
    /// adds each column's ‖y − QQᵀy‖² on the range to its residual, and returns the rank of
    /// Q; `None` when `factor` has no span for the range.
    fn compress_range(
        &mut self,
        factor: &dyn FactoredMass,
        y: MatRef<'_, f64>,
        range: Range<usize>,
        (alive, at): (usize, usize),
    ) -> Option<usize> {
        let g = range.len();
        let mut basis = self.basis.as_mut().submatrix_mut(0, 0, g, 6);
        if !factor.wrench_span(range.clone(), basis.rb_mut()) {
            return None;
        }
        let rank = orthonormalize(basis);
        let q = self.basis.as_ref().submatrix(0, 0, g, rank);
        let segment = y.submatrix(range.start, 0, g, alive);
        let p = y.ncols();
        let mut coordinates = self.y.as_mut().submatrix_mut(at, 0, rank, p);
        let (mut alive_part, mut rest) = coordinates.rb_mut().split_at_col_mut(alive);
        matmul(alive_part.rb_mut(), Accum::Replace, q.transpose(), segment, 1.0, Par::Seq);
        rest.fill(0.0);
        for first in (0..alive).step_by(RESIDUAL_CHUNK) {
            let count = RESIDUAL_CHUNK.min(alive - first);
            let mut residual = self.residual.as_mut().submatrix_mut(0, 0, g, count);
            residual.copy_from(segment.subcols(first, count));
            let coordinates = alive_part.rb().subcols(first, count);
            matmul(residual.rb_mut(), Accum::Add, q, coordinates, -1.0, Par::Seq);
            for (k, sum) in self.residuals[first..first + count].iter_mut().enumerate() {
                let r = col_slice(residual.rb().col(k));
                *sum += dot(r, r);
            }
        }
        Some(rank)
    }

    /// Y_R with the compressed ranges' rows replaced by their coordinates, and each column's
    /// support in it: the product's input after [`CompressedSpans::compress`] returned true.
    pub(crate) fn compressed(&self) -> (MatRef<'_, f64>, &[usize]) {
        (self.y.as_ref(), &self.support)
    }

    /// Whether every column's dropped residual is within the bound (module docs), given the
    /// product `w` formed from the compressed rows (its diagonal W_jj = ‖y_j‖² − ‖r_j‖²).
    pub(crate) fn within_bound(&self, w: MatRef<'_, f64>) -> bool {
        let bound = RESIDUAL_BOUND * RESIDUAL_BOUND;
        self.residuals.iter().enumerate().all(|(j, &r)| r <= bound * (w[(j, j)] + r))
    }

    /// Forgets the compressed ranges (the product was formed without them).
    pub(crate) fn discard(&mut self) {
        self.spans.clear();
    }

    /// Rows the last [`CompressedSpans::compress`] left out: Σ (e − s − k) over its ranges.
    pub(crate) fn rows_saved(&self) -> usize {
        self.spans.iter().map(|span| span.dofs.len() - span.rank).sum()
    }
}

/// Where DOF position `e` (a column's support) falls in the compressed rows: past every
/// range that ends at or before it, each of which became k rows; inside a range (a support a
/// promise left out), past its k rows (the column is zero from `e` on, so its coordinates
/// there are all it has).
fn compressed_position(spans: &[Span], e: usize) -> usize {
    let mut removed = 0;
    for span in spans {
        if span.dofs.end <= e {
            removed += span.dofs.len() - span.rank;
        } else if span.dofs.start < e {
            return span.dofs.start - removed + span.rank;
        }
    }
    e - removed
}

/// A column of a column-major view as a slice.
fn col_slice(column: faer::ColRef<'_, f64>) -> &[f64] {
    column.try_as_col_major().expect("a column-major view's columns are contiguous").as_slice()
}

/// Orthonormalises the columns of `basis` in place by classical Gram–Schmidt run twice
/// (orthogonal to rounding), dropping a column within 10⁻¹⁰ of the span of those before it
/// (relative to its norm; zero or non-finite columns too); returns how many are kept, packed
/// first.
fn orthonormalize(mut basis: MatMut<'_, f64>) -> usize {
    let mut rank = 0;
    for j in 0..basis.ncols() {
        let original = column_norm(basis.rb(), j);
        if !(original > 0.0 && original.is_finite()) {
            continue;
        }
        for _ in 0..2 {
            for i in 0..rank {
                let projection: f64 =
                    (0..basis.nrows()).map(|a| basis[(a, i)] * basis[(a, j)]).sum();
                for a in 0..basis.nrows() {
                    basis[(a, j)] -= projection * basis[(a, i)];
                }
            }
        }
        let remaining = column_norm(basis.rb(), j);
        if remaining <= 1e-10 * original {
            continue;
        }
        for a in 0..basis.nrows() {
            basis[(a, rank)] = basis[(a, j)] / remaining;
        }
        rank += 1;
    }
    rank
}

/// ‖column j of `m`‖₂.
fn column_norm(m: MatRef<'_, f64>, j: usize) -> f64 {
    let column = col_slice(m.col(j));
    dot(column, column).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn supports_move_past_the_rows_a_range_saved() {
        // [24, 60) became 6 rows and [90, 130) 5: 36 − 6 = 30 and 40 − 5 = 35 rows fewer.
        let spans = [Span { dofs: 24..60, rank: 6 }, Span { dofs: 90..130, rank: 5 }];
        let moved = [0, 24, 40, 60, 75, 90, 100, 130, 140].map(|e| compressed_position(&spans, e));
        assert_eq!(moved, [0, 24, 30, 30, 45, 60, 65, 65, 75]);
    }

    #[test]
    fn the_basis_is_orthonormal_and_drops_dependent_columns() {
        // Columns of very different sizes (1e6 and 1), one a combination of two before it,
        // one zero.
        let mut basis = Mat::from_fn(9, 6, |a, j| {
            let scale = if j == 1 { 1e6 } else { 1.0 };
            let value = ((a * 37 + j * 101 + a * j * 17) % 23) as f64 / 23.0 - 0.5;
            if j == 4 { 0.0 } else { value * scale }
        });
        for a in 0..9 {
            basis[(a, 2)] = 3.0 * basis[(a, 0)] - 2e-6 * basis[(a, 1)];
        }
        let original = basis.clone();
        let rank = orthonormalize(basis.as_mut());
        assert_eq!(rank, 4, "the combination and the zero column are dropped");
        for i in 0..rank {
            for j in 0..rank {
                let product: f64 = (0..9).map(|a| basis[(a, i)] * basis[(a, j)]).sum();
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((product - expected).abs() < 1e-14, "QᵀQ[{i}, {j}] = {product}");
            }
        }
        // Every original column lies in the span: its residual is at rounding level.
        for j in 0..6 {
            let column: Vec<f64> = (0..9).map(|a| original[(a, j)]).collect();
            let coordinates: Vec<f64> =
                (0..rank).map(|i| (0..9).map(|a| basis[(a, i)] * column[a]).sum()).collect();
            let residual: f64 = (0..9)
                .map(|a| column[a] - (0..rank).map(|i| basis[(a, i)] * coordinates[i]).sum::<f64>())
                .map(|r| r * r)
                .sum::<f64>()
                .sqrt();
            let size = column.iter().map(|c| c * c).sum::<f64>().sqrt();
            assert!(residual <= 1e-14 * size.max(1e-300), "column {j}: residual {residual:e}");
        }
    }
}
