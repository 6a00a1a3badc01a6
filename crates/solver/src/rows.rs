//! Constraint rows: the generic container that the body-model row builders fill.
//!
//! Row i is a dense n-vector cᵢ over the reduced velocities q̇, a right-hand side bᵢ, a
//! [`RowKind`] and a [`RowGroup`]:
//!
//! | kind | constraint | multiplier λᵢ |
//! |---|---|---|
//! | `Equality` | cᵢᵀq̇ = bᵢ | free |
//! | `Inequality` | cᵢᵀq̇ ≥ bᵢ | λᵢ ≥ 0 |
//! | `SoftInequality { weight }` | cᵢᵀq̇ + σᵢ ≥ bᵢ, σᵢ ≥ 0, cost weight·σᵢ | 0 ≤ λᵢ ≤ weight |
//!
//! For all rows the solve satisfies M̃q̇ = f̃ + Cᵀλ, so an inequality row *pushes* along +cᵢ.
//! The soft penalty is exact: whenever the hard problem is feasible with λᵢ < weight the
//! solution is the hard one; "slack used" means λᵢ reached the weight.
//!
//! Storage: the coefficients sit in one column-major n × capacity matrix whose column i is
//! cᵢ, i.e. the columns form Cᵀ. That is the layout the contact-space solve needs (it copies
//! Cᵀ and solves L Y = Cᵀ in place) and each row is one contiguous slice. Capacity only grows:
//! [`Rows::clear`] keeps every buffer, so refilling the same number of rows each step does not
//! allocate.

use faer::{Mat, MatRef};

use crate::error::SolverError;

/// How a row constrains q̇ (see the module table). Soft rows carry their penalty weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RowKind {
    /// Bilateral row cᵀq̇ = b (head fixation): λ free.
    Equality,
    /// Unilateral row cᵀq̇ ≥ b (limits, wall, self contact): λ ≥ 0.
    Inequality,
    /// Penalised unilateral row cᵀq̇ + σ ≥ b with σ ≥ 0 costing `weight`·σ (thigmotaxis):
    /// 0 ≤ λ ≤ weight. Keeps the QP feasible when such rows conflict with hard ones.
    SoftInequality {
        /// Penalty per unit of slack (impulse units, g·cm/s for a point row); finite, > 0.
        weight: f64,
    },
}

impl RowKind {
    /// True for rows with a sign-constrained multiplier (hard or soft inequalities); their
    /// presence selects the QP path.
    pub fn is_inequality(self) -> bool {
        !matches!(self, RowKind::Equality)
    }
}

/// What a row models. Results (row counts, generalized impulses) are reported per group as
/// `[T; RowGroup::COUNT]` arrays indexed by [`RowGroup::index`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum RowGroup {
    /// Head fixation (bilateral rows on the root DOFs).
    Head,
    /// Joint limits.
    Limit,
    /// Wall contact.
    Wall,
    /// Self contact on the centreline.
    Contact,
    /// Thigmotaxic velocity targets.
    Thigmo,
}

impl RowGroup {
    /// Number of groups, the length of every per-group array.
    pub const COUNT: usize = 5;
    /// All groups in index order.
    pub const ALL: [RowGroup; RowGroup::COUNT] =
        [RowGroup::Head, RowGroup::Limit, RowGroup::Wall, RowGroup::Contact, RowGroup::Thigmo];

    /// Position of the group in per-group arrays (`ALL[g.index()] == g`).
    pub const fn index(self) -> usize {
        self as usize
    }
}

/// Grow-only container of constraint rows over `dofs` reduced velocities.
#[derive(Debug, Clone)]
pub struct Rows {
    /// n × capacity, column-major; column i holds cᵢ (so the first `len` columns are Cᵀ).
    coefficients: Mat<f64>,
    rhs: Vec<f64>,
    kinds: Vec<RowKind>,
    groups: Vec<RowGroup>,
}

impl Rows {
    /// An empty container for rows over `dofs` velocities.
    pub fn new(dofs: usize) -> Self {
        Self::with_capacity(dofs, 0)
    }

    /// An empty container with room for `capacity` rows before it reallocates.
    pub fn with_capacity(dofs: usize, capacity: usize) -> Self {
        Self {
            coefficients: Mat::zeros(dofs, capacity),
            rhs: Vec::with_capacity(capacity),
            kinds: Vec::with_capacity(capacity),
            groups: Vec::with_capacity(capacity),
        }
    }

    /// Number of DOFs n (length of every coefficient vector).
    pub fn dofs(&self) -> usize {
        self.coefficients.nrows()
    }

    /// Number of rows m.
    pub fn len(&self) -> usize {
        self.rhs.len()
    }

    /// True when there are no rows (the unconstrained path).
    pub fn is_empty(&self) -> bool {
        self.rhs.is_empty()
    }

    /// Removes all rows, keeping the capacity (no allocation when refilled to the same size).
    pub fn clear(&mut self) {
        self.rhs.clear();
        self.kinds.clear();
        self.groups.clear();
    }

    /// Removes all rows and switches to `dofs` velocities (reallocates only if n changes).
    pub fn reset(&mut self, dofs: usize) {
        self.clear();
        if dofs != self.dofs() {
            self.coefficients = Mat::zeros(dofs, self.coefficients.ncols());
        }
    }

    /// Appends the row `coefficients`ᵀq̇ (kind) `rhs` and returns its index. Fails when the
    /// slice length is not n. Values are checked when a [`Problem`](crate::Problem) is built.
    pub fn push(
        &mut self,
        kind: RowKind,
        group: RowGroup,
        rhs: f64,
        coefficients: &[f64],
    ) -> Result<usize, SolverError> {
        if coefficients.len() != self.dofs() {
            return Err(SolverError::DimensionMismatch {
                what: "row coefficients",
                expected: self.dofs(),
                found: coefficients.len(),
            });
        }
        self.push_zeroed(kind, group, rhs).copy_from_slice(coefficients);
        Ok(self.len() - 1)
    }

    /// Appends a row with zero coefficients and returns them for the builder to fill in place
    /// (sparse rows such as a joint limit eₖ set one entry; no temporary vector needed).
    pub fn push_zeroed(&mut self, kind: RowKind, group: RowGroup, rhs: f64) -> &mut [f64] {
        let index = self.len();
        if index == self.coefficients.ncols() {
            self.grow();
        }
        self.rhs.push(rhs);
        self.kinds.push(kind);
        self.groups.push(group);
        let column = self.coefficients.col_as_slice_mut(index);
        column.fill(0.0);
        column
    }

    /// Coefficients cᵢ of row `index`, or `None` past the end.
    pub fn coefficients(&self, index: usize) -> Option<&[f64]> {
        (index < self.len()).then(|| self.coefficients.col_as_slice(index))
    }

    /// Coefficients cᵢ of a row known to exist (crate-internal indices only).
    pub(crate) fn row(&self, index: usize) -> &[f64] {
        self.coefficients.col_as_slice(index)
    }

    /// Right-hand sides b (one per row).
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }

    /// Right-hand sides b, to change a bound between solves (e.g. a contact row tightened after
    /// predicting the end-of-step gap); the coefficients stay.
    pub fn rhs_mut(&mut self) -> &mut [f64] {
        &mut self.rhs
    }

    /// Row kinds (one per row).
    pub fn kinds(&self) -> &[RowKind] {
        &self.kinds
    }

    /// Row groups (one per row).
    pub fn groups(&self) -> &[RowGroup] {
        &self.groups
    }

    /// Cᵀ as an n × m view: column i is cᵢ.
    pub fn transposed(&self) -> MatRef<'_, f64> {
        self.coefficients.as_ref().subcols(0, self.len())
    }

    /// Number of rows in each group, indexed by [`RowGroup::index`].
    pub fn count_per_group(&self) -> [usize; RowGroup::COUNT] {
        let mut counts = [0; RowGroup::COUNT];
        for group in &self.groups {
            counts[group.index()] += 1;
        }
        counts
    }

    /// True when any row is a (hard or soft) inequality, which selects the QP path.
    pub fn has_inequalities(&self) -> bool {
        self.kinds.iter().any(|kind| kind.is_inequality())
    }

    /// Doubles the row capacity (at least 8), keeping the existing rows.
    fn grow(&mut self) {
        let dofs = self.dofs();
        let capacity = (2 * self.coefficients.ncols()).max(8);
        let mut grown = Mat::zeros(dofs, capacity);
        grown.as_mut().subcols_mut(0, self.len()).copy_from(self.transposed());
        self.coefficients = grown;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn push_stores_rows_as_columns_of_c_transpose() -> Result<(), SolverError> {
        let mut rows = Rows::new(3);
        rows.push(RowKind::Equality, RowGroup::Head, 1.0, &[1.0, 0.0, 0.0])?;
        let limit = rows.push_zeroed(RowKind::Inequality, RowGroup::Limit, -2.0);
        limit[2] = -1.0;
        assert_eq!(rows.len(), 2);
        assert_eq!(rows.coefficients(1), Some(&[0.0, 0.0, -1.0][..]));
        assert_eq!(rows.coefficients(2), None);
        assert_eq!(rows.transposed()[(2, 1)], -1.0);
        assert_eq!(rows.rhs(), &[1.0, -2.0]);
        assert_eq!(rows.count_per_group(), [1, 1, 0, 0, 0]);
        assert!(rows.has_inequalities());
        Ok(())
    }

    #[test]
    fn wrong_length_is_a_dimension_error() {
        let mut rows = Rows::new(3);
        let result = rows.push(RowKind::Inequality, RowGroup::Wall, 0.0, &[1.0]);
        assert!(matches!(
            result,
            Err(SolverError::DimensionMismatch { expected: 3, found: 1, .. })
        ));
        assert!(rows.is_empty());
    }

    #[test]
    fn growing_keeps_rows_and_clear_keeps_capacity() -> Result<(), SolverError> {
        let mut rows = Rows::new(2);
        for i in 0..20 {
            let value = f64::from(i);
            rows.push(RowKind::Inequality, RowGroup::Contact, value, &[value, -value])?;
        }
        assert_eq!(rows.coefficients(13), Some(&[13.0, -13.0][..]));
        let capacity = rows.coefficients.ncols();
        rows.clear();
        assert!(rows.is_empty() && !rows.has_inequalities());
        rows.push_zeroed(RowKind::Equality, RowGroup::Head, 0.0);
        assert_eq!(rows.coefficients.ncols(), capacity);
        assert_eq!(rows.coefficients(0), Some(&[0.0, 0.0][..]));
        rows.reset(4);
        assert_eq!((rows.dofs(), rows.len()), (4, 0));
        Ok(())
    }

    #[test]
    fn group_indices_match_all() {
        for (i, group) in RowGroup::ALL.iter().enumerate() {
            assert_eq!(group.index(), i);
        }
    }
}
