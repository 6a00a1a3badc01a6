//! The columns a contact-space build solves L⁻¹ for: each row's own coefficients, or, for rows
//! made of base vectors ([`RowBasis::Combination`]), their three bases once (`rows.rs`). Row i
//! is then `cᵢ = Σ_t w_t r_{j_t}` over its terms (column j_t of the reduced set, weight w_t):
//! one term of weight 1 for a row of its own, three for a combination. With E the m × p
//! matrix of the terms, Y = Y_R Eᵀ and W = E W_R Eᵀ: a friction pyramid of 8 edges costs the
//! solves and the product YᵀY of 3 columns instead of 8.

use crate::error::SolverError;
use crate::linalg::try_capacity;
use crate::rows::{RowBasis, Rows};
use crate::wrench_breaks::WrenchBreaks;

/// What a reduced column is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ReducedColumn {
    /// Row i's own coefficients.
    Row(usize),
    /// Base vector k of the rows.
    Base(usize),
}

/// Row i's terms: `(reduced column, weight)`, the first `count` of them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Terms {
    terms: [(usize, f64); 3],
    count: usize,
}

impl Terms {
    /// The terms in use.
    pub(crate) fn as_slice(&self) -> &[(usize, f64)] {
        &self.terms[..self.count]
    }
}

/// The reduced columns of one build and each row's terms.
#[derive(Debug, Default)]
pub(crate) struct ReducedRows {
    columns: Vec<ReducedColumn>,
    terms: Vec<Terms>,
    /// While [`ReducedRows::reduce`] runs: the reduced column of each base vector, or
    /// `usize::MAX` before it is met (not renumbered by [`ReducedRows::reorder`]).
    base_column: Vec<usize>,
    /// Scratch of [`ReducedRows::reorder`].
    reordered: Vec<ReducedColumn>,
}

impl ReducedRows {
    /// Room for `rows` rows (and as many reduced columns).
    pub(crate) fn try_reserve(&mut self, rows: usize) -> Result<(), SolverError> {
        try_capacity(&mut self.columns, rows, "the reduced columns")?;
        try_capacity(&mut self.reordered, rows, "the reduced columns")?;
        try_capacity(&mut self.terms, rows, "the rows' terms")
    }

    /// The reduced columns of `rows`: a row of its own is its own column; a combination's
    /// three bases are columns from the first row that uses them on.
    pub(crate) fn reduce(&mut self, rows: &Rows) {
        self.columns.clear();
        self.terms.clear();
        self.base_column.clear();
        for (i, basis) in rows.basis().iter().enumerate() {
            let terms = match *basis {
                RowBasis::Own => {
                    self.columns.push(ReducedColumn::Row(i));
                    Terms { terms: [(self.columns.len() - 1, 1.0); 3], count: 1 }
                }
                RowBasis::Combination { first, weights } => {
                    if self.base_column.len() < first + 3 {
                        self.base_column.resize(first + 3, usize::MAX);
                    }
                    let mut terms = [(0, 0.0); 3];
                    for (k, term) in terms.iter_mut().enumerate() {
                        if self.base_column[first + k] == usize::MAX {
                            self.base_column[first + k] = self.columns.len();
                            self.columns.push(ReducedColumn::Base(first + k));
                        }
                        *term = (self.base_column[first + k], weights[k]);
                    }
                    Terms { terms, count: 3 }
                }
            };
            self.terms.push(terms);
        }
    }

    /// Renumbers the columns so that column k is the old column `order[k]` (`order` a
    /// permutation of 0..p) and the rows' terms name them so; `position` is scratch (p).
    pub(crate) fn reorder(&mut self, order: &[usize], position: &mut Vec<usize>) {
        position.clear();
        position.resize(order.len(), 0);
        for (k, &j) in order.iter().enumerate() {
            position[j] = k;
        }
        self.reordered.clear();
        self.reordered.extend(order.iter().map(|&j| self.columns[j]));
        std::mem::swap(&mut self.columns, &mut self.reordered);
        for terms in &mut self.terms {
            for (column, _) in &mut terms.terms[..terms.count] {
                *column = position[*column];
            }
        }
    }

    /// Number of reduced columns p.
    pub(crate) fn len(&self) -> usize {
        self.columns.len()
    }

    /// Reduced column `j`'s coefficients in `rows`.
    pub(crate) fn column<'r>(&self, rows: &'r Rows, j: usize) -> &'r [f64] {
        match self.columns[j] {
            ReducedColumn::Row(i) => rows.own_row(i),
            ReducedColumn::Base(k) => rows.base(k),
        }
    }

    /// The breaks promised for reduced column j (`wrench_breaks.rs`), `None` for none.
    pub(crate) fn breaks<'r>(&self, rows: &'r Rows, j: usize) -> Option<&'r WrenchBreaks> {
        match self.columns[j] {
            ReducedColumn::Row(i) => rows.breaks(i),
            ReducedColumn::Base(k) => rows.base_breaks(k),
        }
    }

    /// Row i's terms.
    pub(crate) fn terms(&self, i: usize) -> &[(usize, f64)] {
        self.terms[i].as_slice()
    }

    /// The reduced column that is row i itself, or `None` for a combination.
    pub(crate) fn own_column(&self, i: usize) -> Option<usize> {
        match self.terms[i].as_slice() {
            &[(column, _)] => Some(column),
            _ => None,
        }
    }

    /// The row that reduced column `j` is, or `None` for a base.
    pub(crate) fn own_row(&self, j: usize) -> Option<usize> {
        match self.columns[j] {
            ReducedColumn::Row(i) => Some(i),
            ReducedColumn::Base(_) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rows::{RowKind, RowSource, RowTag};

    #[test]
    fn a_combination_s_bases_are_columns_once_and_its_rows_their_weights() {
        let mut rows = Rows::new(2);
        let source = RowSource::new(RowTag::new(0), 0);
        rows.push_zeroed(RowKind::Inequality, source, 0.0).copy_from_slice(&[1.0, 2.0]);
        let first = rows.push_bases();
        for (base, values) in
            rows.bases_mut(first).into_iter().zip([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
        {
            base.copy_from_slice(&values);
        }
        for weights in [[1.0, 2.0, 3.0], [0.5, 0.0, -1.0]] {
            rows.push_combination(RowKind::Inequality, source, 0.0, (first, weights));
        }
        assert_eq!(rows.coefficients_of(1).to_vec(), [4.0, 5.0]);
        assert_eq!(rows.coefficients_of(2).to_vec(), [-0.5, -1.0]);
        let mut reduced = ReducedRows::default();
        reduced.reduce(&rows);
        assert_eq!(reduced.len(), 4, "one row of its own and three bases");
        assert_eq!(reduced.terms(0), [(0, 1.0)]);
        assert_eq!(reduced.terms(2), [(1, 0.5), (2, 0.0), (3, -1.0)]);
        assert_eq!(reduced.column(&rows, 3), [1.0, 1.0]);
        assert_eq!((reduced.own_column(0), reduced.own_column(1)), (Some(0), None));
        assert_eq!((reduced.own_row(0), reduced.own_row(2)), (Some(0), None));
    }
}
