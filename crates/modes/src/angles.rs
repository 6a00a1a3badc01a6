//! Comparing bases across runs and bodies: mode shapes resampled on a common s/L grid, the
//! principal angles between two subspaces, and the energy of a field that another basis
//! captures.

use faer::Mat;
use hagfish_anatomy::interpolate_clamped;

use crate::error::ModesError;
use crate::field::Field;
use crate::pod::thin_svd;

/// A singular value below this fraction of the largest marks a dependent basis vector.
const RANK_TOLERANCE: f64 = 1e-12;

/// `points` ≥ 2 equally spaced values of s/L from 0 to 1: a grid on which the modes of bodies
/// of any resolution compare.
pub fn uniform_grid(points: usize) -> Vec<f64> {
    let last = points.max(2) - 1;
    (0..=last).map(|i| i as f64 / last as f64).collect()
}

/// Each of `shapes` (sampled at the strictly increasing s/L values `at_l`) at the s/L values of
/// `grid`, by linear interpolation, clamped beyond the ends.
pub fn resample(
    at_l: &[f64],
    shapes: &[Vec<f64>],
    grid: &[f64],
) -> Result<Vec<Vec<f64>>, ModesError> {
    if at_l.len() < 2 || at_l.windows(2).any(|w| w[1] <= w[0]) {
        return Err(ModesError::Invalid(
            "mode shapes must be sampled at ≥ 2 strictly increasing arc lengths (one DOF kind)"
                .into(),
        ));
    }
    Ok(shapes
        .iter()
        .map(|v| grid.iter().map(|&x| interpolate_clamped(at_l, v, x)).collect())
        .collect())
}

/// An orthonormal basis Q (as columns) of the span of `vectors` (all of one length): the left
/// singular vectors of the matrix of columns with σ > 1e-12 σ₁.
fn orthonormal(vectors: &[Vec<f64>], what: &str) -> Result<Mat<f64>, ModesError> {
    let rows = vectors.first().map_or(0, Vec::len);
    if rows == 0 || vectors.iter().any(|v| v.len() != rows || v.iter().any(|x| !x.is_finite())) {
        return Err(ModesError::Invalid(format!(
            "{what}: the vectors must be finite, non-empty and of one length"
        )));
    }
    let matrix = Mat::from_fn(rows, vectors.len(), |i, j| vectors[j][i]);
    let svd = thin_svd(matrix.as_ref(), what)?;
    let sigma = svd.S().column_vector();
    let largest = if sigma.nrows() > 0 { sigma[0] } else { 0.0 };
    let rank = (0..sigma.nrows()).filter(|&i| sigma[i] > RANK_TOLERANCE * largest).count();
    if rank == 0 {
        return Err(ModesError::Invalid(format!("{what}: the vectors are all zero")));
    }
    Ok(svd.U().subcols(0, rank).to_owned())
}

/// The principal angles (rad, increasing) between span(`a`) and span(`b`), bases given as
/// vectors sampled on one grid: with Q₁, Q₂ orthonormal bases of the two spans (Q₂ the one of
/// lower rank), cos θᵢ are the singular values of Q₁ᵀQ₂ and sin θᵢ those of Q₂ − Q₁Q₁ᵀQ₂
/// (Björck and Golub); an angle below π/4 is taken from its sine, which keeps small angles
/// accurate (the cosine of 10⁻⁸ rad is 1 in f64). min(rank a, rank b) angles; 0 for a
/// direction the spans share, π/2 for one orthogonal to the other span.
pub fn principal_angles(a: &[Vec<f64>], b: &[Vec<f64>]) -> Result<Vec<f64>, ModesError> {
    let (qa, qb) = (orthonormal(a, "the first basis")?, orthonormal(b, "the second basis")?);
    if qa.nrows() != qb.nrows() {
        return Err(ModesError::Invalid(format!(
            "the bases are sampled at {} and {} points: resample them on one grid",
            qa.nrows(),
            qb.nrows()
        )));
    }
    let (q1, q2) = if qa.ncols() >= qb.ncols() { (qa, qb) } else { (qb, qa) };
    let product = q1.transpose() * &q2;
    let svd = thin_svd(product.as_ref(), "Q₁ᵀQ₂")?;
    let cosines = svd.S().column_vector();
    let rest = &q2 - &q1 * &product;
    let sines = thin_svd(rest.as_ref(), "Q₂ − Q₁Q₁ᵀQ₂")?;
    let sines = sines.S().column_vector();
    let count = cosines.nrows();
    Ok((0..count)
        .map(|i| {
            let cosine = cosines[i].clamp(0.0, 1.0);
            // The sines come largest first: the i-th smallest angle has the i-th smallest sine.
            let sine = sines[count - 1 - i].clamp(0.0, 1.0);
            if cosine > std::f64::consts::FRAC_1_SQRT_2 { sine.asin() } else { cosine.acos() }
        })
        .collect())
}

/// The fraction of `field`'s energy in the span of `basis` (mode shapes of another run,
/// sampled at the increasing s/L values `basis_l`): the basis is resampled at the field's
/// s/L, orthonormalized to Q, and the fraction is ‖F Q‖² / ‖F‖² (1 when the field lies in the
/// span). The field must be of one DOF kind, its arc lengths increasing.
pub fn captured_energy(
    field: &Field,
    basis_l: &[f64],
    basis: &[Vec<f64>],
) -> Result<f64, ModesError> {
    let at = field.arcs_l();
    if at.windows(2).any(|w| w[1] <= w[0]) {
        return Err(ModesError::Invalid(format!(
            "{}: the DOFs' arc lengths must increase (select one DOF kind)",
            field.label
        )));
    }
    let q = orthonormal(&resample(basis_l, basis, &at)?, "the basis")?;
    let projected = field.matrix() * &q;
    let captured: f64 = (0..projected.ncols())
        .flat_map(|j| (0..projected.nrows()).map(move |i| (i, j)))
        .map(|(i, j)| projected[(i, j)].powi(2))
        .sum();
    Ok(captured / field.energy())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resampling_is_exact_at_the_marks_and_linear_between() {
        let grid = uniform_grid(5);
        assert_eq!(grid, [0.0, 0.25, 0.5, 0.75, 1.0]);
        let shapes = resample(&[0.0, 0.5, 1.0], &[vec![0.0, 1.0, 0.0]], &grid).expect("resampled");
        assert_eq!(shapes[0], [0.0, 0.5, 1.0, 0.5, 0.0]);
        assert!(resample(&[0.0, 0.0], &[vec![0.0, 1.0]], &grid).is_err());
    }
}
