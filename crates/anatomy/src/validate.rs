//! Physical validation of [`Biometrics`]: every check names the field, and a caller that has
//! the source text turns the field into a `file:line:column` (see `locate`).

use crate::biometrics::{Biometrics, MAX_BODY_COUNT};
use crate::error::{AnatomyError, Field, Origin};

/// The admissible range of a real-valued field.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Bound {
    /// Finite and > 0 (lengths, masses, circumferences).
    Positive,
    /// Finite and ≥ 0 (stiffness, damping).
    NonNegative,
    /// In the open interval (0, 1) (arc-length fractions).
    Fraction,
    /// In the open interval (0°, 180°) (joint limits).
    Angle,
}

impl Bound {
    fn admits(self, v: f64) -> bool {
        v.is_finite()
            && match self {
                Bound::Positive => v > 0.0,
                Bound::NonNegative => v >= 0.0,
                Bound::Fraction => v > 0.0 && v < 1.0,
                Bound::Angle => v > 0.0 && v < 180.0,
            }
    }

    fn expected(self) -> &'static str {
        match self {
            Bound::Positive => "finite and > 0",
            Bound::NonNegative => "finite and ≥ 0",
            Bound::Fraction => "a fraction of the length in (0, 1)",
            Bound::Angle => "an angle in (0°, 180°)",
        }
    }
}

/// Runs the checks with one way of turning a field into an [`Origin`].
pub(crate) struct Checker<'a> {
    pub(crate) locate: &'a dyn Fn(&Field) -> Origin,
}

impl Checker<'_> {
    pub(crate) fn value(&self, field: Field, value: f64, bound: Bound) -> Result<(), AnatomyError> {
        if bound.admits(value) {
            return Ok(());
        }
        let at = (self.locate)(&field);
        Err(AnatomyError::OutOfRange { at, field, value, expected: bound.expected().into() })
    }

    /// Checks an array: one entry per mark, each within `bound`.
    fn per_mark(
        &self,
        name: &'static str,
        values: &[f64],
        marks: usize,
        bound: Bound,
    ) -> Result<(), AnatomyError> {
        if values.len() != marks {
            let field = Field::whole(name);
            let at = (self.locate)(&field);
            return Err(AnatomyError::LengthMismatch {
                at,
                field,
                got: values.len(),
                expected: marks,
            });
        }
        for (k, &v) in values.iter().enumerate() {
            self.value(Field::element(name, k), v, bound)?;
        }
        Ok(())
    }

    fn marks(&self, marks: &[f64]) -> Result<(), AnatomyError> {
        const NAME: &str = "mark_fractions";
        if marks.is_empty() {
            return Err(AnatomyError::NoMarks { at: (self.locate)(&Field::whole(NAME)) });
        }
        self.per_mark(NAME, marks, marks.len(), Bound::Fraction)?;
        match marks.windows(2).position(|w| w[1] <= w[0]) {
            None => Ok(()),
            Some(k) => {
                let field = Field::element(NAME, k + 1);
                let at = (self.locate)(&field);
                Err(AnatomyError::NotIncreasing {
                    at,
                    field,
                    value: marks[k + 1],
                    previous: marks[k],
                })
            }
        }
    }

    fn body_count(&self, name: &'static str, n: usize) -> Result<(), AnatomyError> {
        if (2..=MAX_BODY_COUNT).contains(&n) {
            return Ok(());
        }
        let field = Field::whole(name);
        Err(AnatomyError::OutOfRange {
            at: (self.locate)(&field),
            field,
            value: n as f64,
            expected: format!("an integer from 2 to {MAX_BODY_COUNT}"),
        })
    }
}

impl Biometrics {
    /// Checks that every value is physically meaningful: L, M, circumferences and the taper's
    /// tip radius finite and > 0; mark fractions strictly increasing in (0, 1); bending and
    /// twist limits in (0°, 180°); stiffness and damping finite and ≥ 0; one circumference
    /// and one bending limit per mark; 2 ≤ N, N_ref ≤ [`MAX_BODY_COUNT`]. Errors carry
    /// [`Origin::InMemory`]; [`Biometrics::from_ron`] reports file positions instead.
    pub fn validate(&self) -> Result<(), AnatomyError> {
        self.validate_with(&|_| Origin::InMemory)
    }

    /// [`Biometrics::validate`], placing each error with `locate`.
    pub(crate) fn validate_with(
        &self,
        locate: &dyn Fn(&Field) -> Origin,
    ) -> Result<(), AnatomyError> {
        let check = Checker { locate };
        check.value(Field::whole("length_cm"), self.length_cm, Bound::Positive)?;
        check.value(Field::whole("mass_g"), self.mass_g, Bound::Positive)?;
        check.marks(&self.mark_fractions)?;
        let marks = self.mark_fractions.len();
        check.per_mark("circumferences_cm", &self.circumferences_cm, marks, Bound::Positive)?;
        check.per_mark("bending_limits_deg", &self.bending_limits_deg, marks, Bound::Angle)?;
        check.value(Field::whole("twist_limit_deg"), self.twist_limit_deg, Bound::Angle)?;
        for (name, value) in [
            ("bending_stiffness_dyn_cm_per_rad", self.bending_stiffness_dyn_cm_per_rad),
            ("twist_stiffness_dyn_cm_per_rad", self.twist_stiffness_dyn_cm_per_rad),
            ("damping_dyn_cm_s_per_rad", self.damping_dyn_cm_s_per_rad),
        ] {
            check.value(Field::whole(name), value, Bound::NonNegative)?;
        }
        check.body_count("body_count", self.body_count)?;
        check.body_count("reference_body_count", self.reference_body_count)?;
        if let Some(skin) = &self.skin {
            check.value(
                Field::whole("skin.thickness_fraction"),
                skin.thickness_fraction,
                Bound::Fraction,
            )?;
            check.value(
                Field::whole("skin.pressure_dyn_per_cm2"),
                skin.pressure_dyn_per_cm2,
                Bound::Positive,
            )?;
        }
        if let Some(taper) = &self.tail_taper {
            check.value(
                Field::whole("tail_taper.tip_radius_cm"),
                taper.tip_radius_cm,
                Bound::Positive,
            )?;
        }
        Ok(())
    }
}
