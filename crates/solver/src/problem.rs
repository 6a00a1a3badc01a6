//! The velocity problem of one step, validated once.
//!
//! minimize ½ q̇ᵀM̃q̇ − q̇ᵀf̃ subject to the [`Rows`], with M̃ = M_r + hD + h²K (n × n, symmetric
//! positive definite) and f̃ = M_r q̇⁰ + h f_r. Its optimality (KKT) conditions, in the sign
//! convention of the whole crate, are
//!
//! M̃q̇ = f̃ + Cᵀλ,  λ free on equalities, λ ≥ 0 ⟂ (Cq̇ − b) on inequalities,
//! 0 ≤ λ ≤ weight on soft inequalities (with slack σ = max(0, b − Cq̇) where λ = weight).
//!
//! [`Problem::new`] checks every input once (sizes, finiteness, symmetry of M̃, soft weights),
//! so the solver itself never sees malformed data. Positive definiteness is checked by the
//! Cholesky factorisation during the solve.

use faer::linalg::matmul::matmul;
use faer::{Accum, MatRef, Par};

use crate::error::SolverError;
use crate::linalg::{column, column_mut, norm_max};
use crate::mass_operator::{Mass, MassOperator};
use std::sync::atomic::{AtomicBool, Ordering};

use crate::rows::{RowBasis, RowKind, Rows};

/// Relative tolerance of the symmetry check: |M̃ᵢⱼ − M̃ⱼᵢ| ≤ tol·(|M̃ᵢⱼ| + |M̃ⱼᵢ|) + tol·max|M̃ₖₖ|.
const SYMMETRY_TOLERANCE: f64 = 1e-12;

/// Borrowed, validated inputs of one velocity solve: M̃, f̃, the rows and their right-hand
/// sides b (the rows' own, or new ones given to a [`Factored`](crate::Factored) solve).
#[derive(Debug, Clone, Copy)]
pub struct Problem<'a> {
    mass: Mass<'a>,
    force: &'a [f64],
    rows: &'a Rows,
    rhs: &'a [f64],
    /// A flag that, once set, ends the solve with [`SolverError::Stopped`] (polled between the
    /// blocks of W and the active set's iterations).
    stop: Option<&'a AtomicBool>,
}

impl<'a> Problem<'a> {
    /// Validates and wraps M̃ (`mass`, n × n, symmetric; the upper triangle is factored and the
    /// full matrix enters the residuals), f̃ (`force`, length n) and the rows (over n DOFs).
    pub fn new(
        mass: MatRef<'a, f64>,
        force: &'a [f64],
        rows: &'a Rows,
    ) -> Result<Self, SolverError> {
        Self::with_mass(Mass::Dense(mass), rows)?.with_force_and_rhs(force, rows.rhs())
    }

    /// Validates and wraps an effective mass given as an operator with its own factor
    /// (`mass`, n DOFs; symmetric positive definite by its contract), f̃ (`force`, length n)
    /// and the rows (over n DOFs). The workspace uses the operator's factor instead of
    /// factoring a dense M̃.
    pub fn with_operator(
        mass: &'a dyn MassOperator,
        force: &'a [f64],
        rows: &'a Rows,
    ) -> Result<Self, SolverError> {
        Self::with_mass(Mass::Operator(mass), rows)?.with_force_and_rhs(force, rows.rhs())
    }

    /// Validates M̃ (sizes, finiteness, symmetry of a dense one) and the rows' coefficients and
    /// soft weights; f̃ and b are still empty (see [`Problem::with_force_and_rhs`]).
    pub(crate) fn with_mass(mass: Mass<'a>, rows: &'a Rows) -> Result<Self, SolverError> {
        let n = rows.dofs();
        match mass {
            Mass::Dense(matrix) => {
                check_size("mass matrix rows", n, matrix.nrows())?;
                check_size("mass matrix columns", n, matrix.ncols())?;
                check_mass(matrix)?;
            }
            Mass::Operator(operator) => check_size("mass operator", n, operator.dofs())?,
        }
        check_rows(rows)?;
        Ok(Self { mass, force: &[], rows, rhs: &[], stop: None })
    }

    /// The same M̃ and rows with f̃ = `force` (length n) and b = `rhs` (one per row), both
    /// checked (sizes, finiteness).
    pub(crate) fn with_force_and_rhs<'b>(
        self,
        force: &'b [f64],
        rhs: &'b [f64],
    ) -> Result<Problem<'b>, SolverError>
    where
        'a: 'b,
    {
        check_size("force", self.rows.dofs(), force.len())?;
        check_size("row rhs", self.rows.len(), rhs.len())?;
        for (i, &value) in force.iter().enumerate() {
            check_finite("force", i, 0, value)?;
        }
        for (i, &value) in rhs.iter().enumerate() {
            check_finite("row rhs", i, 0, value)?;
        }
        Ok(Problem { mass: self.mass, force, rows: self.rows, rhs, stop: self.stop })
    }

    /// The same problem, its solve ended with [`SolverError::Stopped`] once `flag` is set.
    pub fn stopping_when(self, flag: Option<&'a AtomicBool>) -> Self {
        Self { stop: flag, ..self }
    }

    /// [`SolverError::Stopped`] if the stop flag is set.
    pub(crate) fn check_stop(&self) -> Result<(), SolverError> {
        match self.stop {
            Some(flag) if flag.load(Ordering::Relaxed) => Err(SolverError::Stopped),
            _ => Ok(()),
        }
    }

    /// The stop flag, if any.
    pub(crate) fn stop(&self) -> Option<&'a AtomicBool> {
        self.stop
    }

    /// M̃: a dense matrix or an operator.
    pub fn mass(&self) -> Mass<'a> {
        self.mass
    }

    /// out ← M̃x (both of length n), with the original data (the dense matrix or the
    /// operator's own product).
    pub fn apply_mass(&self, x: &[f64], out: &mut [f64]) {
        match self.mass {
            Mass::Dense(mass) => {
                matmul(column_mut(out), Accum::Replace, mass, column(x), 1.0, Par::Seq);
            }
            Mass::Operator(operator) => operator.apply(x, out),
        }
    }

    /// f̃, length n.
    pub fn force(&self) -> &'a [f64] {
        self.force
    }

    /// The constraint rows (their coefficients, kinds and sources; the right-hand sides in
    /// use are [`Problem::rhs`]).
    pub fn rows(&self) -> &'a Rows {
        self.rows
    }

    /// The right-hand sides b in use, one per row.
    pub fn rhs(&self) -> &'a [f64] {
        self.rhs
    }

    /// Number of DOFs n.
    pub fn dofs(&self) -> usize {
        self.force.len()
    }
}

fn check_size(what: &'static str, expected: usize, found: usize) -> Result<(), SolverError> {
    if expected == found {
        Ok(())
    } else {
        Err(SolverError::DimensionMismatch { what, expected, found })
    }
}

fn check_finite(what: &'static str, row: usize, col: usize, value: f64) -> Result<(), SolverError> {
    if value.is_finite() { Ok(()) } else { Err(SolverError::NonFinite { what, row, col, value }) }
}

/// Independent partial sums of [`all_finite`] (one running sum is a chain of dependent
/// additions; these vectorise).
const FINITE_LANES: usize = 4;

/// True when every value is finite: Σ 0·v is 0 for finite values and NaN as soon as one is
/// infinite or NaN (branch-free, in [`FINITE_LANES`] partial sums).
fn all_finite(values: &[f64]) -> bool {
    let chunks = values.chunks_exact(FINITE_LANES);
    let tail = chunks.remainder().iter().fold(0.0, |sum, v| sum + v * 0.0);
    let sums = chunks.fold([0.0; FINITE_LANES], |mut sums, chunk| {
        for (sum, v) in sums.iter_mut().zip(chunk) {
            *sum += v * 0.0;
        }
        sums
    });
    sums.iter().fold(tail, |total, sum| total + sum) == 0.0
}

/// Finite entries and symmetry up to rounding. A mirrored assembly (as the tree's CRBA)
/// gives an exactly symmetric M̃, which one cheap pass accepts: every entry finite and equal
/// to its mirror image. Anything else goes to the tolerance check, one branch-free pass over
/// the columns (both triangles at once); only a matrix that fails it is searched again for
/// the first offending entry, so the error is the same as an entry-by-entry check would give.
fn check_mass(mass: MatRef<'_, f64>) -> Result<(), SolverError> {
    if mirrored_and_finite(mass) { Ok(()) } else { check_mass_tolerance(mass) }
}

/// Every entry finite and M̃ᵢⱼ = M̃ⱼᵢ exactly (false also for a matrix that is not
/// column-major, which the tolerance check then handles).
fn mirrored_and_finite(mass: MatRef<'_, f64>) -> bool {
    let mut ok = true;
    for j in 0..mass.ncols() {
        let Some(column) = mass.col(j).try_as_col_major().map(|c| c.as_slice()) else {
            return false;
        };
        ok &= all_finite(column);
        for (&upper, &lower) in column[..j].iter().zip(mass.row(j).iter()) {
            ok &= upper == lower;
        }
    }
    ok
}

/// The tolerance check of [`check_mass`].
fn check_mass_tolerance(mass: MatRef<'_, f64>) -> Result<(), SolverError> {
    let n = mass.nrows();
    let max_diagonal = (0..n).fold(0.0_f64, |m, j| m.max(mass[(j, j)].abs()));
    let mut bad = !max_diagonal.is_finite();
    for j in 0..n {
        // Column j above the diagonal (contiguous) against row j left of it (strided).
        let Some(column) = mass.col(j).try_as_col_major().map(|c| c.as_slice()) else {
            bad = true;
            break;
        };
        for (&upper, &lower) in column[..j].iter().zip(mass.row(j).iter()) {
            let tolerance = SYMMETRY_TOLERANCE * (upper.abs() + lower.abs() + max_diagonal);
            bad |= !(upper.is_finite() & lower.is_finite() & ((upper - lower).abs() <= tolerance));
        }
        bad |= !column[j].is_finite();
    }
    if bad { first_mass_error(mass, max_diagonal) } else { Ok(()) }
}

/// The first non-finite entry (column by column), else the first asymmetric pair.
fn first_mass_error(mass: MatRef<'_, f64>, max_diagonal: f64) -> Result<(), SolverError> {
    let n = mass.nrows();
    for j in 0..n {
        for i in 0..n {
            check_finite("mass matrix", i, j, mass[(i, j)])?;
        }
    }
    for j in 0..n {
        for i in 0..j {
            let (upper, lower) = (mass[(i, j)], mass[(j, i)]);
            let tolerance = SYMMETRY_TOLERANCE * (upper.abs() + lower.abs() + max_diagonal);
            if (upper - lower).abs() > tolerance {
                return Err(SolverError::NotSymmetric { row: i, col: j, upper, lower });
            }
        }
    }
    Ok(())
}

/// A friction row `row` of `kinds` with normal row `normal` and coefficient μ: μ finite and
/// ≥ 0, the normal row an inequality row just before the contact's first friction row, at
/// most two friction rows per contact.
fn check_friction(
    kinds: &[RowKind],
    row: usize,
    normal: usize,
    coefficient: f64,
) -> Result<(), SolverError> {
    let invalid = |reason: String| Err(SolverError::InvalidFriction { row, reason });
    if !(coefficient.is_finite() && coefficient >= 0.0) {
        return invalid(format!("coefficient {coefficient} must be finite and ≥ 0"));
    }
    match kinds.get(normal) {
        Some(RowKind::Inequality) => {}
        Some(kind) => {
            return invalid(format!("normal row {normal} is {kind:?}, not an inequality"));
        }
        None => {
            return invalid(format!("normal row {normal} does not exist ({} rows)", kinds.len()));
        }
    }
    let same_contact = |k: usize| matches!(kinds.get(k), Some(RowKind::Friction { normal: n, .. }) if *n == normal);
    let first = if row >= 1 && same_contact(row - 1) { row - 1 } else { row };
    if normal + 1 != first {
        return invalid(format!(
            "its normal row {normal} is not the row just before its contact's"
        ));
    }
    if row >= 2 && same_contact(row - 1) && same_contact(row - 2) {
        return invalid(format!("a third consecutive friction row of normal row {normal}"));
    }
    Ok(())
}

/// Finite coefficients, valid soft weights and compliances (the right-hand sides are checked with f̃). The
/// coefficients are checked in one branch-free pass ([`coefficients_finite`]); only when it
/// fails are they searched for the first offending entry.
fn check_rows(rows: &Rows) -> Result<(), SolverError> {
    let finite = coefficients_finite(rows);
    for (i, &kind) in rows.kinds().iter().enumerate() {
        if let RowKind::SoftInequality { weight } = kind
            && !(weight.is_finite() && weight > 0.0)
        {
            return Err(SolverError::InvalidWeight { row: i, weight });
        }
        if let RowKind::Compliant { compliance } = kind
            && !(compliance.is_finite() && compliance > 0.0)
        {
            return Err(SolverError::InvalidCompliance { row: i, compliance });
        }
        if let RowKind::Friction { normal, coefficient } = kind {
            check_friction(rows.kinds(), i, normal, coefficient)?;
        }
        if !finite {
            for (j, c) in rows.coefficients_of(i).iter().enumerate() {
                check_finite("row coefficients", i, j, c)?;
            }
        }
    }
    Ok(())
}

/// True when every row's coefficients are finite, read where they are stored: each row of its
/// own, each combination's bases once (over their extent: zero after it) and each combination
/// Σₖ wₖgₖ by its bound Σₖ|wₖ| maxⱼ|gₖⱼ| (finite and below f64::MAX / 2 ⇒ every entry finite,
/// rounding included), written out only where the bound fails.
fn coefficients_finite(rows: &Rows) -> bool {
    let mut bases: Option<(usize, [f64; 3])> = None;
    rows.basis().iter().zip(rows.extents()).enumerate().all(|(i, (basis, &extent))| match *basis {
        RowBasis::Own => all_finite(rows.own_row(i)),
        RowBasis::Combination { first, weights } => {
            let sizes = match bases {
                Some((last, sizes)) if last == first => sizes,
                _ => {
                    let used = |k: usize| &rows.base(first + k)[..extent];
                    if !(0..3).all(|k| all_finite(used(k))) {
                        return false;
                    }
                    [0, 1, 2].map(|k| norm_max(used(k)))
                }
            };
            bases = Some((first, sizes));
            let bound: f64 = weights.iter().zip(sizes).map(|(w, size)| w.abs() * size).sum();
            bound <= f64::MAX / 2.0 || rows.coefficients_of(i).iter().all(f64::is_finite)
        }
    })
}

#[cfg(test)]
mod tests {
    use faer::Mat;

    use super::*;
    use crate::rows::{RowSource, RowTag};

    #[test]
    fn accepts_a_well_formed_problem() -> Result<(), SolverError> {
        let mass = Mat::<f64>::identity(2, 2);
        let mut rows = Rows::new(2);
        rows.push(RowKind::Inequality, RowSource::new(RowTag::new(2), 0), 0.0, &[1.0, 0.0])?;
        let problem = Problem::new(mass.as_ref(), &[1.0, 2.0], &rows)?;
        assert_eq!(problem.dofs(), 2);
        assert_eq!(problem.rows().len(), 1);
        Ok(())
    }

    #[test]
    fn rejects_size_mismatches() {
        let mass = Mat::<f64>::identity(2, 2);
        let rows = Rows::new(2);
        let err = Problem::new(mass.as_ref(), &[1.0, 2.0, 3.0], &rows).err();
        // n is the rows' number of DOFs; M̃ and f̃ are measured against it.
        assert!(matches!(
            err,
            Some(SolverError::DimensionMismatch { what: "force", expected: 2, found: 3 })
        ));
        let rows3 = Rows::new(3);
        let err = Problem::new(mass.as_ref(), &[1.0, 2.0], &rows3).err();
        assert!(matches!(
            err,
            Some(SolverError::DimensionMismatch {
                what: "mass matrix rows",
                expected: 3,
                found: 2
            })
        ));
    }

    #[test]
    fn all_finite_sees_every_position_of_every_length() {
        for len in 0..=11 {
            let mut values: Vec<f64> = (0..len).map(|i| 1e300 * (i as f64 - 4.5)).collect();
            assert!(all_finite(&values), "length {len}");
            for i in 0..len {
                for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let kept = std::mem::replace(&mut values[i], bad);
                    assert!(!all_finite(&values), "length {len}, {bad} at {i}");
                    values[i] = kept;
                }
            }
        }
    }

    #[test]
    fn rejects_non_finite_values_with_their_position() -> Result<(), SolverError> {
        let mut mass = Mat::<f64>::identity(2, 2);
        let rows = Rows::new(2);
        let err = Problem::new(mass.as_ref(), &[0.0, f64::NAN], &rows).err();
        assert!(matches!(err, Some(SolverError::NonFinite { what: "force", row: 1, .. })));
        mass[(1, 0)] = f64::INFINITY;
        let err = Problem::new(mass.as_ref(), &[0.0, 0.0], &rows).err();
        assert!(matches!(
            err,
            Some(SolverError::NonFinite { what: "mass matrix", row: 1, col: 0, .. })
        ));
        let mass = Mat::<f64>::identity(2, 2);
        let mut rows = Rows::new(2);
        rows.push(RowKind::Inequality, RowSource::new(RowTag::new(3), 0), 0.0, &[1.0, f64::NAN])?;
        let err = Problem::new(mass.as_ref(), &[0.0, 0.0], &rows).err();
        assert!(matches!(
            err,
            Some(SolverError::NonFinite { what: "row coefficients", row: 0, col: 1, .. })
        ));
        Ok(())
    }

    /// A combination row is checked through its bases and the bound Σₖ|wₖ| maxⱼ|gₖⱼ|, and
    /// written out where the bound fails: entries that overflow are refused at their position,
    /// finite ones under a bound beyond f64::MAX / 2 pass, a NaN in a base is refused.
    #[test]
    fn combination_rows_are_checked_where_they_are_stored() {
        let mass = Mat::<f64>::identity(2, 2);
        let source = RowSource::new(RowTag::new(3), 0);
        let problem_with = |bases: [[f64; 2]; 2], weights: [f64; 3]| {
            let mut rows = Rows::new(2);
            let first = rows.push_bases();
            let [g0, g1, _] = rows.bases_mut(first);
            g0.copy_from_slice(&bases[0]);
            g1.copy_from_slice(&bases[1]);
            rows.push_combination(RowKind::Inequality, source, 0.0, (first, weights));
            Problem::new(mass.as_ref(), &[0.0, 0.0], &rows).err()
        };
        let big = 1e308;
        assert_eq!(problem_with([[big, 0.0], [0.0, big]], [0.6, 0.6, 0.0]), None);
        assert!(matches!(
            problem_with([[big, 0.0], [0.0, big]], [0.6, 2.0, 0.0]),
            Some(SolverError::NonFinite { what: "row coefficients", row: 0, col: 1, .. })
        ));
        assert!(matches!(
            problem_with([[1.0, f64::NAN], [0.0, 1.0]], [0.5, 0.5, 0.0]),
            Some(SolverError::NonFinite { what: "row coefficients", row: 0, col: 1, .. })
        ));
    }

    #[test]
    fn accepts_rounding_level_asymmetry() -> Result<(), SolverError> {
        // Not mirrored exactly, so the tolerance check decides: 1e-15 relative passes.
        let mut mass = Mat::<f64>::identity(2, 2);
        mass[(0, 1)] = 0.5;
        mass[(1, 0)] = 0.5 * (1.0 + 1e-15);
        let rows = Rows::new(2);
        Problem::new(mass.as_ref(), &[0.0, 0.0], &rows)?;
        Ok(())
    }

    #[test]
    fn rejects_asymmetric_mass_and_bad_weights() -> Result<(), SolverError> {
        let mut mass = Mat::<f64>::identity(2, 2);
        mass[(0, 1)] = 0.5;
        let rows = Rows::new(2);
        let err = Problem::new(mass.as_ref(), &[0.0, 0.0], &rows).err();
        assert!(matches!(err, Some(SolverError::NotSymmetric { row: 0, col: 1, .. })));
        let mass = Mat::<f64>::identity(2, 2);
        let mut rows = Rows::new(2);
        let soft = RowKind::SoftInequality { weight: -1.0 };
        rows.push(soft, RowSource::new(RowTag::new(4), 0), 1.0, &[1.0, 0.0])?;
        let err = Problem::new(mass.as_ref(), &[0.0, 0.0], &rows).err();
        assert!(matches!(err, Some(SolverError::InvalidWeight { row: 0, .. })));
        Ok(())
    }
}
