//! Constraint rows: the generic container that the body-model row builders fill.
//!
//! Row i is a dense n-vector cᵢ over the reduced velocities q̇, a right-hand side bᵢ, a
//! [`RowKind`] and a [`RowSource`] (the caller's [`RowTag`] and id, never interpreted here):
//!
//! | kind | constraint | multiplier λᵢ |
//! |---|---|---|
//! | `Equality` | cᵢᵀq̇ = bᵢ | free |
//! | `Inequality` | cᵢᵀq̇ ≥ bᵢ | λᵢ ≥ 0 |
//! | `SoftInequality { weight }` | cᵢᵀq̇ + σᵢ ≥ bᵢ, σᵢ ≥ 0, cost weight·σᵢ | 0 ≤ λᵢ ≤ weight |
//! | `Compliant { compliance }` | cᵢᵀq̇ + εᵢλᵢ ≥ bᵢ, complementary to λᵢ | λᵢ ≥ 0 |
//! | `Friction { normal, coefficient }` | with its contact's normal row: v_n ≥ μ‖v_t‖ | ‖λ_t‖ ≤ μλ_n |
//!
//! For all rows the solve satisfies M̃q̇ = f̃ + Cᵀλ, so an inequality row *pushes* along +cᵢ.
//! The soft penalty is exact: whenever the hard problem is feasible with λᵢ < weight the
//! solution is the hard one; "slack used" means λᵢ reached the weight.
//!
//! A compliant row is an implicit spring: with ε = 1/(k h²) and b = −g/h for a gap g, the
//! impulse is λ = h·k·max(0, −(g + h cᵀq̇)), the force of a spring of stiffness k at the end of
//! the step (backward Euler). In the primal it costs ½σᵢ²/εᵢ for a violation σᵢ = εᵢλᵢ; in the
//! contact space it adds εᵢ to Wᵢᵢ, so it is never linearly dependent. A nearly rigid one
//! (εᵢ ≲ 1e-6·cᵢᵀM̃⁻¹cᵢ) on a row that depends on others has a pivot εᵢ that cancels against
//! Wᵢᵢ and loses digits; the solve then reports `SolvedInexact` (a skin's ε is ≈ 0.3–3 times
//! its row's mobility at h = 0.01 s).
//!
//! A friction row is one tangent direction of a contact whose normal row is `normal`: with
//! v_n = c_nᵀq̇ − b_n and v_t the tangent rows' cₜᵀq̇ − bₜ, the contact's impulse lies in
//! Coulomb's cone ‖λ_t‖ ≤ μλ_n and its velocity in the dual cone v_n ≥ μ‖v_t‖, complementary
//! (λ_n v_n + λ_t·v_t = 0): Anitescu's convex relaxation of Coulomb's law, whose sliding
//! contacts take the force −μλ_n v_t/‖v_t‖ (maximal dissipation) and a normal velocity μ‖v_t‖
//! (`pyramid.rs`). The clarabel backend solves the cone exactly; the contact-space backend
//! refuses it, and takes the cone's inscribed pyramid as plain inequality rows instead
//! ([`crate::FrictionPyramid`]).
//!
//! A row may be stored as a combination of three base vectors, `cᵢ = Σₖ wₖ g_{f+k}`
//! ([`Rows::push_bases`], [`Rows::push_combination`]): a contact's rows along the edges of its
//! friction pyramid are all `dᵀG` for the same 3 × n Jacobian G of the contact's relative
//! velocity. Such a row is kept as its bases and weights and never written out: the
//! contact-space build solves L⁻¹ for the three bases once instead of once per row
//! (`reduced_rows.rs`), and the few readers of a row's coefficients (the rows with λᵢ ≠ 0, a
//! predicted overshoot) write them out entry by entry as they read them
//! ([`RowCoefficients`]). The bases must be filled before their rows are pushed, and kept.
//!
//! Storage: the coefficients of rows of their own sit in one column-major n × capacity matrix
//! whose column i is cᵢ (a combination's column is left unused), so each row is one
//! contiguous slice, the layout the contact-space solve reads. Capacity only grows:
//! [`Rows::clear`] keeps every buffer, so refilling the same number of rows each step does not
//! allocate.

use faer::Mat;

use crate::error::SolverError;
use crate::linalg::{try_capacity, try_matrix_capacity};
use crate::row_coefficients::RowCoefficients;
use crate::wrench_breaks::WrenchBreaks;

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
    /// Compliant unilateral row cᵀq̇ + ελ ≥ b, λ ≥ 0, complementary (a skin's implicit
    /// spring, see the module docs): λ ≥ 0.
    Compliant {
        /// ε (1/g for a point row: velocity per impulse), finite and > 0.
        compliance: f64,
    },
    /// One tangent direction of a contact's friction cone (see the module docs): a contact is
    /// its normal row followed by its one or two friction rows, which name it, and the cone
    /// is ‖λ_t‖ ≤ μλ_n. Solved exactly by the clarabel backend only.
    Friction {
        /// Index of the contact's normal row (an `Inequality` row).
        normal: usize,
        /// The friction coefficient μ, finite and ≥ 0.
        coefficient: f64,
    },
}

impl RowKind {
    /// True for rows with a constrained multiplier (hard, soft or compliant inequalities and
    /// friction); their presence selects the QP path.
    pub fn is_inequality(self) -> bool {
        !matches!(self, RowKind::Equality)
    }

    /// The row's compliance ε: its own for a compliant row, 0 for every other kind.
    pub fn compliance(self) -> f64 {
        match self {
            RowKind::Compliant { compliance } => compliance,
            _ => 0.0,
        }
    }
}

/// The caller's label for what a row models (a joint limit, a wall, a contact, …): an opaque
/// id below [`RowTag::COUNT`] that the caller maps to its own meaning. The solver never
/// interprets it; reports count rows ([`PerTag`]) and sum impulses
/// ([`SolverWorkspace::tag_impulse`](crate::SolverWorkspace::tag_impulse)) per tag.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct RowTag(u8);

impl RowTag {
    /// Number of distinct tags, the length of every [`PerTag`] array.
    pub const COUNT: usize = 16;

    /// The tag `id`, `id` < [`RowTag::COUNT`].
    ///
    /// # Panics
    /// When `id` ≥ [`RowTag::COUNT`]; in a `const` item that is a compile error, so define
    /// tags as constants (`const WALL: RowTag = RowTag::new(2);`).
    pub const fn new(id: u8) -> Self {
        assert!((id as usize) < Self::COUNT, "a row tag is below RowTag::COUNT");
        Self(id)
    }

    /// Position of the tag in per-tag arrays (its id).
    pub const fn index(self) -> usize {
        self.0 as usize
    }
}

/// Where a row comes from: the caller's [`RowTag`] and the caller's id of the object that
/// produced it (which contact, which DOF), so that a row and its multiplier can be traced back
/// to their source without relying on row order (MuJoCo's `efc_type`/`efc_id`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RowSource {
    /// What the row models.
    pub tag: RowTag,
    /// The caller's index of the object the row constrains (a contact, a DOF, a body).
    pub id: usize,
}

impl RowSource {
    /// The source `id` of kind `tag`.
    pub const fn new(tag: RowTag, id: usize) -> Self {
        Self { tag, id }
    }
}

/// One value per [`RowTag`] (row counts, active rows), indexed by the tag.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PerTag<T>([T; RowTag::COUNT]);

impl<T> PerTag<T> {
    /// The values in tag order, with their tags.
    pub fn iter(&self) -> impl Iterator<Item = (RowTag, &T)> {
        (0..).map(RowTag).zip(&self.0)
    }
}

impl<T> core::ops::Index<RowTag> for PerTag<T> {
    type Output = T;
    fn index(&self, tag: RowTag) -> &T {
        &self.0[tag.index()]
    }
}

impl<T> core::ops::IndexMut<RowTag> for PerTag<T> {
    fn index_mut(&mut self, tag: RowTag) -> &mut T {
        &mut self.0[tag.index()]
    }
}

/// How a row's coefficients are made (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RowBasis {
    /// Its own coefficients.
    Own,
    /// `cᵢ = Σₖ weights[k] · g_{first+k}`, the bases filled through [`Rows::bases_mut`].
    Combination {
        /// The first of its three bases.
        first: usize,
        /// The weights wₖ.
        weights: [f64; 3],
    },
}

/// Grow-only container of constraint rows over `dofs` reduced velocities.
#[derive(Debug, Clone)]
pub struct Rows {
    /// n × capacity, column-major; column i holds cᵢ if row i is a row of its own.
    coefficients: Mat<f64>,
    rhs: Vec<f64>,
    kinds: Vec<RowKind>,
    sources: Vec<RowSource>,
    /// How each row is made.
    basis: Vec<RowBasis>,
    /// Each row's extent: its coefficients vanish from it on (n for a row of its own).
    extents: Vec<usize>,
    /// n × capacity, column-major: the base vectors of combination rows.
    bases: Mat<f64>,
    /// Base vectors in use.
    base_count: usize,
    /// The first base of the last combination and the end of its bases' nonzero entries, so
    /// that a contact's edge rows find it once (cleared when a base is written).
    bases_extent: Option<(usize, usize)>,
    /// The breaks of each row's own coefficients (`wrench_breaks.rs`; `None`: no promise).
    breaks: Vec<Option<WrenchBreaks>>,
    /// The breaks of each base vector (`None`: no promise).
    base_breaks: Vec<Option<WrenchBreaks>>,
}

impl Rows {
    /// An empty container for rows over `dofs` velocities.
    pub fn new(dofs: usize) -> Self {
        Self {
            coefficients: Mat::zeros(dofs, 0),
            rhs: Vec::new(),
            kinds: Vec::new(),
            sources: Vec::new(),
            basis: Vec::new(),
            extents: Vec::new(),
            bases: Mat::zeros(dofs, 0),
            base_count: 0,
            bases_extent: None,
            breaks: Vec::new(),
            base_breaks: Vec::new(),
        }
    }

    /// An empty container with room for `capacity` rows before it reallocates.
    ///
    /// # Errors
    /// [`SolverError::Allocation`] if the room cannot be allocated (`dofs` × `capacity`
    /// coefficients: the largest buffer of a step).
    pub fn try_with_capacity(dofs: usize, capacity: usize) -> Result<Self, SolverError> {
        let mut rows = Self::new(dofs);
        try_matrix_capacity(&mut rows.coefficients, dofs, capacity, "the rows' coefficients")?;
        rows.coefficients.resize_with(dofs, capacity, |_, _| 0.0);
        try_capacity(&mut rows.rhs, capacity, "the rows' right-hand sides")?;
        try_capacity(&mut rows.kinds, capacity, "the rows' kinds")?;
        try_capacity(&mut rows.sources, capacity, "the rows' sources")?;
        try_capacity(&mut rows.basis, capacity, "the rows' bases")?;
        try_capacity(&mut rows.extents, capacity, "the rows' extents")?;
        try_capacity(&mut rows.breaks, capacity, "the rows' breaks")?;
        Ok(rows)
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
        self.sources.clear();
        self.basis.clear();
        self.extents.clear();
        self.breaks.clear();
        self.base_breaks.clear();
        self.base_count = 0;
        self.bases_extent = None;
    }

    /// Removes all rows and switches to `dofs` velocities (reallocates only if n changes).
    pub fn reset(&mut self, dofs: usize) {
        self.clear();
        if dofs != self.dofs() {
            self.coefficients = Mat::zeros(dofs, self.coefficients.ncols());
            self.bases = Mat::zeros(dofs, self.bases.ncols());
        }
    }

    /// Appends the row `coefficients`ᵀq̇ (kind) `rhs` and returns its index. Fails when the
    /// slice length is not n. Values are checked when a [`Problem`](crate::Problem) is built.
    pub fn push(
        &mut self,
        kind: RowKind,
        source: RowSource,
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
        self.push_zeroed(kind, source, rhs).copy_from_slice(coefficients);
        Ok(self.len() - 1)
    }

    /// Appends a row with zero coefficients and returns them for the builder to fill in place
    /// (sparse rows such as a joint limit eₖ set one entry; no temporary vector needed).
    pub fn push_zeroed(&mut self, kind: RowKind, source: RowSource, rhs: f64) -> &mut [f64] {
        let index = self.push_row(kind, source, rhs, RowBasis::Own, self.dofs());
        let column = self.coefficients.col_as_slice_mut(index);
        column.fill(0.0);
        column
    }

    /// Appends a row's kind, source, right-hand side, basis and extent, with room for its
    /// coefficients (as they were: the caller writes them), and returns its index.
    fn push_row(
        &mut self,
        kind: RowKind,
        source: RowSource,
        rhs: f64,
        basis: RowBasis,
        extent: usize,
    ) -> usize {
        let index = self.len();
        if index == self.coefficients.ncols() {
            self.grow();
        }
        self.rhs.push(rhs);
        self.kinds.push(kind);
        self.sources.push(source);
        self.basis.push(basis);
        self.extents.push(extent);
        self.breaks.push(None);
        index
    }

    /// Appends three zeroed base vectors and returns the index of the first; fill them with
    /// [`Rows::bases_mut`], then make rows of them with [`Rows::push_combination`].
    pub fn push_bases(&mut self) -> usize {
        let first = self.base_count;
        while self.base_count + 3 > self.bases.ncols() {
            let capacity = (2 * self.bases.ncols()).max(12);
            let mut grown = Mat::zeros(self.dofs(), capacity);
            grown.as_mut().subcols_mut(0, first).copy_from(self.bases.as_ref().subcols(0, first));
            self.bases = grown;
        }
        self.base_count += 3;
        for k in first..first + 3 {
            self.bases.col_as_slice_mut(k).fill(0.0);
        }
        self.base_breaks.extend([None; 3]);
        first
    }

    /// Promises that row `index`'s own coefficients have their breaks at `breaks`
    /// (`wrench_breaks.rs`): the contact space may then compress the DOF ranges between them.
    /// Does nothing for a combination row (its bases carry the breaks) or past the end.
    pub fn set_breaks(&mut self, index: usize, breaks: WrenchBreaks) {
        if let (Some(slot), Some(RowBasis::Own)) =
            (self.breaks.get_mut(index), self.basis.get(index))
        {
            *slot = Some(breaks);
        }
    }

    /// Promises that the three bases pushed at `first` have their breaks at `breaks`.
    pub fn set_base_breaks(&mut self, first: usize, breaks: WrenchBreaks) {
        for slot in self.base_breaks.iter_mut().skip(first).take(3) {
            *slot = Some(breaks);
        }
    }

    /// The breaks promised for row `index`'s own coefficients ([`Rows::set_breaks`]); `None`
    /// for none, for a combination row, or past the end.
    pub fn breaks(&self, index: usize) -> Option<&WrenchBreaks> {
        self.breaks.get(index)?.as_ref()
    }

    /// The breaks promised for base vector `index` (crate-internal indices only).
    pub(crate) fn base_breaks(&self, index: usize) -> Option<&WrenchBreaks> {
        self.base_breaks[index].as_ref()
    }

    /// The three base vectors pushed at `first` by [`Rows::push_bases`], to fill at once.
    pub fn bases_mut(&mut self, first: usize) -> [&mut [f64]; 3] {
        debug_assert!(first + 3 <= self.base_count, "bases {first}.. not pushed");
        self.bases_extent = None;
        let bases = self.bases.as_mut().subcols_mut(first, 3);
        let (g0, rest) = bases.split_at_col_mut(1);
        let (g1, g2) = rest.split_at_col_mut(1);
        [g0, g1, g2].map(|g| {
            g.col_mut(0)
                .try_as_col_major_mut()
                .expect("a Mat's columns are contiguous")
                .as_slice_mut()
        })
    }

    /// Base vector `index` (crate-internal indices only).
    pub(crate) fn base(&self, index: usize) -> &[f64] {
        self.bases.col_as_slice(index)
    }

    /// Appends the row `Σₖ weights[k] · g_{first+k}` (the bases `first..first + 3` must be
    /// filled, and are not to change after), kept as its bases and weights: its extent is the
    /// end of the bases' nonzero entries (the contact's bodies' paths to the root).
    pub fn push_combination(
        &mut self,
        kind: RowKind,
        source: RowSource,
        rhs: f64,
        (first, weights): (usize, [f64; 3]),
    ) {
        let extent = match self.bases_extent {
            Some((bases, extent)) if bases == first => extent,
            _ => {
                let bases = (first..first + 3).map(|k| self.bases.col_as_slice(k));
                let ends = bases.map(|g| g.iter().rposition(|&x| x != 0.0).map_or(0, |e| e + 1));
                ends.max().unwrap_or(0)
            }
        };
        self.bases_extent = Some((first, extent));
        self.push_row(kind, source, rhs, RowBasis::Combination { first, weights }, extent);
    }

    /// How each row is made (one per row).
    pub fn basis(&self) -> &[RowBasis] {
        &self.basis
    }

    /// True when some row is a combination of bases.
    pub fn has_combinations(&self) -> bool {
        self.basis.iter().any(|b| matches!(b, RowBasis::Combination { .. }))
    }

    /// Coefficients cᵢ of row `index`, or `None` past the end.
    pub fn row(&self, index: usize) -> Option<RowCoefficients<'_>> {
        (index < self.len()).then(|| self.coefficients_of(index))
    }

    /// Coefficients cᵢ of a row known to exist (crate-internal indices only).
    pub(crate) fn coefficients_of(&self, index: usize) -> RowCoefficients<'_> {
        match self.basis[index] {
            RowBasis::Own => RowCoefficients::own(self.own_row(index)),
            RowBasis::Combination { first, weights } => {
                let bases = [first, first + 1, first + 2].map(|k| self.base(k));
                RowCoefficients::combination(bases, weights, self.extents[index])
            }
        }
    }

    /// The coefficients of a row of its own (crate-internal indices only; a combination's
    /// column is unused).
    pub(crate) fn own_row(&self, index: usize) -> &[f64] {
        debug_assert!(matches!(self.basis[index], RowBasis::Own), "row {index} is a combination");
        self.coefficients.col_as_slice(index)
    }

    /// Each row's extent: its coefficients vanish from it on.
    pub(crate) fn extents(&self) -> &[usize] {
        &self.extents
    }

    /// Right-hand sides b (one per row), as pushed; to solve the same rows with other bounds,
    /// pass them to [`Factored::solve`](crate::Factored::solve).
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }

    /// Row kinds (one per row).
    pub fn kinds(&self) -> &[RowKind] {
        &self.kinds
    }

    /// Row sources (one per row): the caller's tag and id of each row.
    pub fn sources(&self) -> &[RowSource] {
        &self.sources
    }

    /// Number of rows with each tag.
    pub fn count_per_tag(&self) -> PerTag<usize> {
        let mut counts = PerTag::default();
        for source in &self.sources {
            counts[source.tag] += 1;
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
        let used = self.coefficients.as_ref().subcols(0, self.len());
        grown.as_mut().subcols_mut(0, self.len()).copy_from(used);
        self.coefficients = grown;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FIXED: RowTag = RowTag::new(0);
    const BOUND: RowTag = RowTag::new(1);

    #[test]
    fn room_that_cannot_be_allocated_is_an_error_not_an_abort() {
        let rows = Rows::try_with_capacity(3, 4).expect("a small room");
        assert_eq!((rows.dofs(), rows.len()), (3, 0));
        // 2⁶⁰ coefficients of 8 bytes overflow the address space: refused, nothing aborts.
        match Rows::try_with_capacity(1 << 40, 1 << 20) {
            Err(SolverError::Allocation { what, bytes }) => {
                assert!(what.starts_with("the rows' coefficients (1099511627776 × 1048576)"));
                assert_eq!(bytes, 1 << 63);
            }
            other => panic!("expected an allocation error, got {other:?}"),
        }
        let mut workspace = crate::SolverWorkspace::new(crate::SolverOptions::default());
        workspace.try_reserve(10, 20).expect("a small workspace");
        let error = workspace.try_reserve(1 << 31, 1 << 31).expect_err("2⁶² values");
        assert!(
            error.to_string().starts_with("cannot allocate Y_R = L⁻¹ of the reduced columns"),
            "{error}"
        );
    }

    #[test]
    fn push_stores_rows_as_columns_of_c_transpose() -> Result<(), SolverError> {
        let mut rows = Rows::new(3);
        rows.push(RowKind::Equality, RowSource::new(FIXED, 7), 1.0, &[1.0, 0.0, 0.0])?;
        let limit = rows.push_zeroed(RowKind::Inequality, RowSource::new(BOUND, 2), -2.0);
        limit[2] = -1.0;
        assert_eq!(rows.len(), 2);
        assert_eq!(rows.row(1).map(|r| r.to_vec()), Some(vec![0.0, 0.0, -1.0]));
        assert!(rows.row(2).is_none());
        assert_eq!(rows.rhs(), &[1.0, -2.0]);
        assert_eq!(rows.sources()[0], RowSource::new(FIXED, 7));
        let counts = rows.count_per_tag();
        assert_eq!((counts[FIXED], counts[BOUND], counts[RowTag::new(5)]), (1, 1, 0));
        assert!(rows.has_inequalities());
        Ok(())
    }

    #[test]
    fn wrong_length_is_a_dimension_error() {
        let mut rows = Rows::new(3);
        let result = rows.push(RowKind::Inequality, RowSource::new(BOUND, 0), 0.0, &[1.0]);
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
            rows.push(RowKind::Inequality, RowSource::new(BOUND, 0), value, &[value, -value])?;
        }
        assert_eq!(rows.row(13).map(|r| r.to_vec()), Some(vec![13.0, -13.0]));
        let capacity = rows.coefficients.ncols();
        rows.clear();
        assert!(rows.is_empty() && !rows.has_inequalities() && rows.sources().is_empty());
        rows.push_zeroed(RowKind::Equality, RowSource::new(FIXED, 0), 0.0);
        assert_eq!(rows.coefficients.ncols(), capacity);
        assert_eq!(rows.row(0).map(|r| r.to_vec()), Some(vec![0.0, 0.0]));
        rows.reset(4);
        assert_eq!((rows.dofs(), rows.len()), (4, 0));
        Ok(())
    }

    #[test]
    fn per_tag_values_are_indexed_by_their_tag() {
        let mut values = PerTag::default();
        values[RowTag::new(15)] = 3;
        let tags: Vec<_> = values.iter().filter(|(_, v)| **v > 0).map(|(t, _)| t).collect();
        assert_eq!(tags, [RowTag::new(15)]);
        assert_eq!(values.iter().count(), RowTag::COUNT);
    }

    #[test]
    #[should_panic(expected = "below RowTag::COUNT")]
    fn a_tag_beyond_the_count_is_refused() {
        let id = u8::try_from(RowTag::COUNT).unwrap_or(u8::MAX);
        let _ = RowTag::new(id);
    }
}
