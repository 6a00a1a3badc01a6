//! A force field to decompose: a frames × DOFs matrix with the time of each frame, the arc
//! length of each DOF and, where the run had one, the knot's position in each frame.

use crate::error::ModesError;

/// The matrix F (frames × DOFs, dyn·cm, row-major: `values[f * dofs + d]`) of one selection
/// of a run's thigmotaxic force field, not mean-removed: the thesis reads the field as
/// muscle activations, whose zero is meaningful (no force), so the modes describe the field
/// itself, F = U Σ Vᵀ, and not its fluctuation about a mean.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    /// What was selected, for messages and outputs (e.g. `phase slide, bend-y`).
    pub label: String,
    /// Time of each frame (s), increasing.
    pub times: Vec<f64>,
    /// Arc length of each DOF's joint from the head body's centre (cm).
    pub arcs_cm: Vec<f64>,
    /// The body length L (cm), to give arc lengths as s/L.
    pub length_cm: f64,
    /// The knot's position along the body in each frame (cm, `None` without a knot).
    pub knot_cm: Vec<Option<f64>>,
    /// The values, frame after frame.
    pub values: Vec<f64>,
}

impl Field {
    /// A field of `times.len()` frames and `arcs_cm.len()` DOFs; checks the sizes, that the
    /// values are finite, that L > 0 and that the field is not zero everywhere.
    pub fn new(
        label: String,
        times: Vec<f64>,
        arcs_cm: Vec<f64>,
        length_cm: f64,
        knot_cm: Vec<Option<f64>>,
        values: Vec<f64>,
    ) -> Result<Self, ModesError> {
        let (frames, dofs) = (times.len(), arcs_cm.len());
        if frames == 0 || dofs == 0 || values.len() != frames * dofs || knot_cm.len() != frames {
            return Err(ModesError::Invalid(format!(
                "{label}: {} values and {} knot positions for {frames} frames × {dofs} DOFs",
                values.len(),
                knot_cm.len()
            )));
        }
        if !values.iter().chain(&times).chain(&arcs_cm).all(|v| v.is_finite())
            || length_cm.is_nan()
            || length_cm <= 0.0
        {
            return Err(ModesError::Invalid(format!("{label}: a non-finite value or L ≤ 0")));
        }
        if values.iter().all(|v| *v == 0.0) {
            return Err(ModesError::ZeroField { what: label });
        }
        Ok(Self { label, times, arcs_cm, length_cm, knot_cm, values })
    }

    /// Number of frames (rows of F).
    pub fn frames(&self) -> usize {
        self.times.len()
    }

    /// Number of DOFs (columns of F).
    pub fn dofs(&self) -> usize {
        self.arcs_cm.len()
    }

    /// F as a faer matrix.
    pub fn matrix(&self) -> faer::Mat<f64> {
        let dofs = self.dofs();
        faer::Mat::from_fn(self.frames(), dofs, |f, d| self.values[f * dofs + d])
    }

    /// The arc lengths as fractions of the body length, s/L.
    pub fn arcs_l(&self) -> Vec<f64> {
        self.arcs_cm.iter().map(|s| s / self.length_cm).collect()
    }

    /// The squared Frobenius norm ‖F‖² = Σ F², the field's energy.
    pub fn energy(&self) -> f64 {
        self.values.iter().map(|v| v * v).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_finite_values_and_a_non_zero_field_are_required() {
        let make = |values: Vec<f64>| {
            Field::new("f".into(), vec![0.0, 1.0], vec![0.0], 10.0, vec![None; 2], values)
        };
        assert!(make(vec![1.0, 0.0]).is_ok());
        assert!(matches!(make(vec![0.0, 0.0]), Err(ModesError::ZeroField { .. })));
        assert!(matches!(make(vec![1.0]), Err(ModesError::Invalid(_))));
        assert!(matches!(make(vec![1.0, f64::NAN]), Err(ModesError::Invalid(_))));
        assert_eq!(make(vec![3.0, 4.0]).map(|f| f.energy()).ok(), Some(25.0));
    }
}
