//! Names of the knots identified by their Alexander polynomial.

use std::fmt;

use crate::AlexanderPolynomial;

/// A knot type, as far as the Alexander polynomial identifies it.
///
/// The named variants are the prime knots with at most six crossings (Rolfsen names in the
/// comments). Each is recognised by its normalised polynomial alone, so mirror images are
/// not distinguished, and a knot sharing a polynomial with a listed one is reported under
/// that name (e.g. 9₄₆ as [`KnotType::Stevedore`], the Conway knot as [`KnotType::Unknot`]).
/// Any other polynomial is [`KnotType::Other`].
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum KnotType {
    /// 0₁, Δ = 1.
    Unknot,
    /// 3₁, Δ = t² − t + 1, determinant 3.
    Trefoil,
    /// 4₁, Δ = t² − 3t + 1, determinant 5.
    FigureEight,
    /// 5₁, Δ = t⁴ − t³ + t² − t + 1, determinant 5.
    Cinquefoil,
    /// 5₂, Δ = 2t² − 3t + 2, determinant 7.
    ThreeTwist,
    /// 6₁, Δ = 2t² − 5t + 2, determinant 9.
    Stevedore,
    /// 6₂, Δ = t⁴ − 3t³ + 3t² − 3t + 1, determinant 11.
    Knot6_2,
    /// 6₃, Δ = t⁴ − 3t³ + 5t² − 3t + 1, determinant 13.
    Knot6_3,
    /// Any other (normalised) Alexander polynomial.
    Other(AlexanderPolynomial),
}

/// The named knots with their Rolfsen name and normalised Alexander polynomial (coefficients
/// of t⁰, t¹, …).
const TABLE: [(KnotType, &str, &[i64]); 8] = [
    (KnotType::Unknot, "0_1", &[1]),
    (KnotType::Trefoil, "3_1", &[1, -1, 1]),
    (KnotType::FigureEight, "4_1", &[1, -3, 1]),
    (KnotType::Cinquefoil, "5_1", &[1, -1, 1, -1, 1]),
    (KnotType::ThreeTwist, "5_2", &[2, -3, 2]),
    (KnotType::Stevedore, "6_1", &[2, -5, 2]),
    (KnotType::Knot6_2, "6_2", &[1, -3, 3, -3, 1]),
    (KnotType::Knot6_3, "6_3", &[1, -3, 5, -3, 1]),
];

impl KnotType {
    /// The knot whose normalised Alexander polynomial is `polynomial`, or
    /// [`KnotType::Other`] if it is none of the named ones.
    pub fn from_polynomial(polynomial: &AlexanderPolynomial) -> Self {
        TABLE
            .iter()
            .find(|(_, _, coefficients)| polynomial.coefficients() == *coefficients)
            .map_or_else(|| KnotType::Other(polynomial.clone()), |(knot, _, _)| knot.clone())
    }

    /// The normalised Alexander polynomial of this knot type.
    pub fn polynomial(&self) -> AlexanderPolynomial {
        match self {
            KnotType::Other(polynomial) => polynomial.clone(),
            named => TABLE
                .iter()
                .find(|(knot, _, _)| knot == named)
                .and_then(|(_, _, coefficients)| AlexanderPolynomial::normalised(coefficients))
                .unwrap_or_else(AlexanderPolynomial::unknot),
        }
    }

    /// The named knot of Rolfsen name `name` (`"6_2"`), or `None` if it is not one of them.
    pub fn from_rolfsen_name(name: &str) -> Option<Self> {
        TABLE.iter().find(|(_, n, _)| *n == name).map(|(knot, _, _)| knot.clone())
    }

    /// The Rolfsen name (`"3_1"`, …), or `None` for [`KnotType::Other`].
    pub fn rolfsen_name(&self) -> Option<&'static str> {
        TABLE.iter().find(|(knot, _, _)| knot == self).map(|(_, name, _)| *name)
    }
}

/// Writes the Rolfsen name, or `Δ = …` for [`KnotType::Other`].
impl fmt::Display for KnotType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KnotType::Other(polynomial) => write!(f, "Δ = {polynomial}"),
            named => f.write_str(named.rolfsen_name().unwrap_or_default()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_round_trips_and_determinants_match() {
        let determinants = [1, 3, 5, 5, 7, 9, 11, 13];
        for ((knot, _, _), determinant) in TABLE.iter().zip(determinants) {
            let polynomial = knot.polynomial();
            assert!(polynomial.is_knot_polynomial(), "{knot}");
            assert_eq!(polynomial.determinant(), determinant, "{knot}");
            assert_eq!(&KnotType::from_polynomial(&polynomial), knot);
        }
        let other = AlexanderPolynomial::normalised(&[1, -1, 1, -1, 1, -1, 1]).expect("non-zero");
        assert_eq!(KnotType::from_polynomial(&other), KnotType::Other(other.clone()));
        assert_eq!(KnotType::Other(other).to_string(), "Δ = t^6 - t^5 + t^4 - t^3 + t^2 - t + 1");
        assert_eq!(KnotType::Knot6_3.to_string(), "6_3");
    }
}
