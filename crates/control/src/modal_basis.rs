//! An orthonormal basis B (n × k) of a modal force space and its projector `P = B Bᵀ`.

use crate::error::ControlError;

/// k orthonormal columns of length n (column-major), built by Gram–Schmidt with
/// reorthogonalisation from k linearly independent vectors: the basis of
/// [`crate::ForceSpace::Modes`].
#[derive(Clone, Debug, PartialEq)]
pub struct ModalBasis {
    dofs: usize,
    columns: Vec<f64>,
}

/// A vector whose norm after removing its components along the earlier ones is below this
/// fraction of its own norm is taken as dependent on them.
pub const RANK_TOLERANCE: f64 = 1e-10;

impl ModalBasis {
    /// The orthonormal basis of the span of `vectors` (each of length `dofs`): modified
    /// Gram–Schmidt, each vector orthogonalised twice against the earlier columns, then
    /// normalised, `q_j = (v_j − Σ_{i<j} q_i q_iᵀ v_j) / ‖·‖`. Unit vectors come out
    /// unchanged, bit for bit (every subtracted product is zero). Errors on no vectors,
    /// vectors of another length or non-finite, and on a vector within
    /// [`RANK_TOLERANCE`] of the span of the earlier ones (a rank-deficient basis).
    pub fn orthonormal(dofs: usize, vectors: &[Vec<f64>]) -> Result<Self, ControlError> {
        let bad = |v: &Vec<f64>| v.len() != dofs || v.iter().any(|x| !x.is_finite());
        if dofs == 0 || vectors.is_empty() || vectors.iter().any(bad) {
            return Err(ControlError::NotABasis {
                mode: 0,
                reason: "no finite vectors of the body's DOF count",
            });
        }
        let mut columns = Vec::with_capacity(dofs * vectors.len());
        for (j, vector) in vectors.iter().enumerate() {
            let mut v = vector.clone();
            let norm = dot(&v, &v).sqrt();
            for _ in 0..2 {
                for q in columns.chunks_exact(dofs) {
                    let along = dot(q, &v);
                    v.iter_mut().zip(q).for_each(|(x, qi)| *x -= along * qi);
                }
            }
            let rest = dot(&v, &v).sqrt();
            // Not above the tolerance, NaN included.
            let independent = rest.partial_cmp(&(RANK_TOLERANCE * norm));
            if !matches!(independent, Some(std::cmp::Ordering::Greater)) {
                return Err(ControlError::NotABasis {
                    mode: j + 1,
                    reason: "zero, or in the span of the earlier modes on this body's DOFs",
                });
            }
            columns.extend(v.iter().map(|x| x / rest));
        }
        Ok(Self { dofs, columns })
    }

    /// n, the length of each column (the body's DOF count).
    pub fn dofs(&self) -> usize {
        self.dofs
    }

    /// k, the number of columns.
    pub fn modes(&self) -> usize {
        self.columns.len() / self.dofs
    }

    /// Column `j` of B (`j < k`).
    pub fn column(&self, j: usize) -> &[f64] {
        &self.columns[j * self.dofs..(j + 1) * self.dofs]
    }

    /// `c ← B(Bᵀc)`: the orthogonal projection of `row` (length n) onto the span, with
    /// `scratch[..k]` holding `Bᵀc`. O(nk); allocates nothing.
    pub fn project(&self, row: &mut [f64], scratch: &mut [f64]) {
        let scratch = &mut scratch[..self.modes()];
        for (y, q) in scratch.iter_mut().zip(self.columns.chunks_exact(self.dofs)) {
            *y = dot(q, row);
        }
        for (i, c) in row.iter_mut().enumerate() {
            *c = scratch
                .iter()
                .enumerate()
                .fold(0.0, |sum, (j, y)| sum + self.columns[j * self.dofs + i] * y);
        }
    }
}

/// `aᵀb`, summed in index order from zero.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |sum, (x, y)| sum + x * y)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit(n: usize, i: usize) -> Vec<f64> {
        (0..n).map(|k| if k == i { 1.0 } else { 0.0 }).collect()
    }

    #[test]
    fn unit_vectors_project_exactly_and_other_vectors_are_orthonormalised() {
        let identity =
            ModalBasis::orthonormal(3, &[unit(3, 0), unit(3, 1), unit(3, 2)]).expect("basis");
        let mut row = [0.1, -2.5e-7, 3.0];
        identity.project(&mut row, &mut [0.0; 3]);
        assert_eq!(row, [0.1, -2.5e-7, 3.0]);
        let basis =
            ModalBasis::orthonormal(3, &[vec![1.0, 1.0, 0.0], vec![1.0, 0.0, 1.0]]).expect("basis");
        assert!((dot(basis.column(0), basis.column(1))).abs() < 1e-15);
        let mut row = [0.0, 1.0, -1.0];
        basis.project(&mut row, &mut [0.0; 2]);
        let mut again = row;
        basis.project(&mut again, &mut [0.0; 2]);
        assert!(row.iter().zip(again).all(|(a, b)| (a - b).abs() < 1e-15), "P² = P");
    }

    #[test]
    fn a_rank_deficient_set_is_refused_with_its_mode() {
        let error = ModalBasis::orthonormal(2, &[vec![1.0, 2.0], vec![-2.0, -4.0]]);
        assert!(matches!(error, Err(ControlError::NotABasis { mode: 2, .. })), "{error:?}");
        assert!(ModalBasis::orthonormal(2, &[vec![1.0]]).is_err());
        assert!(ModalBasis::orthonormal(2, &[]).is_err());
    }
}
