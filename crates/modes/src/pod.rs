//! The proper orthogonal decomposition of a field: its thin SVD F = U Σ Vᵀ by faer, with the
//! energy of each mode.

use faer::MatRef;

use crate::error::ModesError;
use crate::field::Field;

/// The energy fractions `hagfish modes` reports the number of modes for.
pub const ENERGY_LEVELS: [f64; 3] = [0.90, 0.95, 0.99];

/// The POD of a field F (frames × DOFs): F = Σᵢ σᵢ uᵢ vᵢᵀ with σ₁ ≥ σ₂ ≥ … ≥ 0, r = min(frames,
/// DOFs) modes. Mode i has the shape vᵢ along the body (unit norm over the DOFs) and the time
/// course aᵢ(t) = σᵢ uᵢ(t) (dyn·cm), so that F(t, s) = Σᵢ aᵢ(t) vᵢ(s). Each sign is fixed so
/// that the largest component of vᵢ is positive, which makes the output deterministic.
#[derive(Clone, Debug, PartialEq)]
pub struct Pod {
    /// σᵢ (dyn·cm), non-increasing.
    pub singular_values: Vec<f64>,
    /// vᵢ: one shape per mode, one value per DOF.
    pub shapes: Vec<Vec<f64>>,
    /// aᵢ = σᵢ uᵢ: one time course per mode, one value per frame (dyn·cm).
    pub time_courses: Vec<Vec<f64>>,
}

impl Pod {
    /// The POD of `field` by faer's thin SVD.
    pub fn of(field: &Field) -> Result<Self, ModesError> {
        let svd = thin_svd(field.matrix().as_ref(), &field.label)?;
        let (u, v) = (svd.U(), svd.V());
        let sigma = svd.S().column_vector();
        let mut pod = Self::default_sized(sigma.nrows());
        for i in 0..sigma.nrows() {
            let shape: Vec<f64> = (0..v.nrows()).map(|d| v[(d, i)]).collect();
            let largest =
                shape.iter().copied().fold(0.0, |m: f64, x| if x.abs() > m.abs() { x } else { m });
            let sign = if largest < 0.0 { -1.0 } else { 1.0 };
            pod.singular_values.push(sigma[i]);
            pod.shapes.push(shape.iter().map(|x| sign * x).collect());
            pod.time_courses.push((0..u.nrows()).map(|f| sign * sigma[i] * u[(f, i)]).collect());
        }
        Ok(pod)
    }

    fn default_sized(modes: usize) -> Self {
        Self {
            singular_values: Vec::with_capacity(modes),
            shapes: Vec::with_capacity(modes),
            time_courses: Vec::with_capacity(modes),
        }
    }

    /// Number of modes r = min(frames, DOFs).
    pub fn modes(&self) -> usize {
        self.singular_values.len()
    }

    /// Each mode's energy fraction eᵢ = σᵢ² / Σⱼ σⱼ² (Σσ² = ‖F‖², so they sum to 1).
    pub fn energy_fractions(&self) -> Vec<f64> {
        let total: f64 = self.singular_values.iter().map(|s| s * s).sum();
        self.singular_values.iter().map(|s| s * s / total).collect()
    }

    /// The cumulative energy fractions Σⱼ≤ᵢ eⱼ.
    pub fn cumulative_fractions(&self) -> Vec<f64> {
        let mut sum = 0.0;
        self.energy_fractions()
            .iter()
            .map(|e| {
                sum += e;
                sum
            })
            .collect()
    }

    /// The fewest modes whose cumulative energy reaches `fraction` (at most r; a relative
    /// 1e-12 is allowed for rounding, so a rank-2 field needs 2 modes for 100 %).
    pub fn modes_for(&self, fraction: f64) -> usize {
        let cumulative = self.cumulative_fractions();
        let reached = cumulative.iter().position(|c| *c >= fraction - 1e-12);
        reached.map_or(cumulative.len(), |i| i + 1)
    }
}

/// faer's thin SVD of `matrix` (`what` names it in the error).
pub(crate) fn thin_svd(
    matrix: MatRef<'_, f64>,
    what: &str,
) -> Result<faer::linalg::solvers::Svd<f64>, ModesError> {
    matrix
        .thin_svd()
        .map_err(|e| ModesError::Svd { what: what.to_owned(), reason: format!("{e:?}") })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rank_one_field_has_one_mode_with_all_the_energy() {
        let (times, arcs) = (vec![0.0, 0.1, 0.2], vec![0.0, 1.0, 2.0, 3.0]);
        let (a, v) = ([1.0, -2.0, 0.5], [0.5, 1.0, -1.0, 2.0]);
        let values = a.iter().flat_map(|ai| v.iter().map(move |vj| ai * vj)).collect();
        let field =
            Field::new("rank 1".into(), times, arcs, 10.0, vec![None; 3], values).expect("a field");
        let pod = Pod::of(&field).expect("a POD");
        let energy = pod.energy_fractions();
        assert!((energy[0] - 1.0).abs() < 1e-14, "{energy:?}");
        assert_eq!(pod.modes_for(0.99), 1);
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        for (shape, expected) in pod.shapes[0].iter().zip(v) {
            assert!((shape - expected / norm).abs() < 1e-14, "the sign makes the largest positive");
        }
        for (course, ai) in pod.time_courses[0].iter().zip(a) {
            assert!((course - ai * norm).abs() < 1e-13);
        }
    }
}
