//! Alexander polynomials in normal form.

use std::cmp::Ordering;
use std::fmt;

/// The Alexander polynomial Δ(t) of a knot, in normal form.
///
/// Δ is defined only up to the units ±tᵏ of ℤ[t, t⁻¹]. The normal form multiplies by the
/// unit that makes the lowest power t⁰ and its coefficient positive, so coefficient `i` is
/// the coefficient of tⁱ. For a knot Δ(t) ≐ Δ(1/t), hence the coefficients are palindromic
/// and the leading coefficient is positive as well (e.g. the trefoil is `[1, -1, 1]`,
/// t² − t + 1, and the figure-eight knot `[1, -3, 1]`, t² − 3t + 1).
///
/// The order ([`Ord`]) ranks "simpler" polynomials first: fewer coefficients, then
/// lexicographically smaller ones; the majority vote uses it to break ties deterministically
/// in favour of the simpler knot.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct AlexanderPolynomial {
    coefficients: Vec<i64>,
}

impl AlexanderPolynomial {
    /// Δ = 1, the polynomial of the unknot (and of a few non-trivial knots, e.g. the
    /// Kinoshita–Terasaka knot, which the Alexander polynomial cannot tell apart).
    pub fn unknot() -> Self {
        Self { coefficients: vec![1] }
    }

    /// Normal form of `Σ coefficients[i] tⁱ`: divides by the largest power of t that divides
    /// it, drops trailing zeros and multiplies by −1 if the constant term is negative.
    /// Returns `None` for the zero polynomial (which is not the polynomial of a knot).
    pub fn normalised(coefficients: &[i64]) -> Option<Self> {
        let first = coefficients.iter().position(|&c| c != 0)?;
        let last = coefficients.iter().rposition(|&c| c != 0)?;
        let sign = coefficients[first].signum();
        let coefficients = coefficients[first..=last].iter().map(|&c| sign * c).collect();
        Some(Self { coefficients })
    }

    /// Coefficients of t⁰, t¹, …, in normal form (never empty; the first is positive).
    pub fn coefficients(&self) -> &[i64] {
        &self.coefficients
    }

    /// The knot determinant |Δ(−1)| (3 for the trefoil, 5 for the figure-eight knot),
    /// saturated at `u64::MAX`.
    pub fn determinant(&self) -> u64 {
        let value = self.evaluate_at_unit(-1);
        u64::try_from(value.unsigned_abs()).unwrap_or(u64::MAX)
    }

    /// Whether the polynomial can be the Alexander polynomial of a knot: its coefficients
    /// are palindromic (Δ(t) ≐ Δ(1/t)) and |Δ(1)| = 1. The exact determinant checks every
    /// result against this, which catches coefficients outside its modular range.
    pub fn is_knot_polynomial(&self) -> bool {
        let palindromic = self.coefficients.iter().eq(self.coefficients.iter().rev());
        palindromic && self.evaluate_at_unit(1).abs() == 1
    }

    /// Δ(±1) in i128 (no overflow: at most a few thousand coefficients below 2⁶³).
    fn evaluate_at_unit(&self, t: i128) -> i128 {
        self.coefficients.iter().rev().fold(0i128, |acc, &c| acc * t + i128::from(c))
    }
}

impl Ord for AlexanderPolynomial {
    fn cmp(&self, other: &Self) -> Ordering {
        self.coefficients
            .len()
            .cmp(&other.coefficients.len())
            .then_with(|| self.coefficients.cmp(&other.coefficients))
    }
}

impl PartialOrd for AlexanderPolynomial {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Writes the polynomial in descending powers, e.g. `t^2 - 3t + 1`.
impl fmt::Display for AlexanderPolynomial {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut first = true;
        for (power, &c) in self.coefficients.iter().enumerate().rev() {
            if c == 0 {
                continue;
            }
            let sign = match (first, c < 0) {
                (true, true) => "-",
                (true, false) => "",
                (false, true) => " - ",
                (false, false) => " + ",
            };
            let magnitude = c.unsigned_abs();
            let number =
                if magnitude == 1 && power > 0 { String::new() } else { magnitude.to_string() };
            let variable = match power {
                0 => String::new(),
                1 => "t".to_owned(),
                _ => format!("t^{power}"),
            };
            write!(f, "{sign}{number}{variable}")?;
            first = false;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_form_strips_powers_of_t_and_sign() {
        let p = AlexanderPolynomial::normalised(&[0, 0, -1, 3, -1, 0]);
        assert_eq!(p.as_ref().map(AlexanderPolynomial::coefficients), Some(&[1, -3, 1][..]));
        assert_eq!(AlexanderPolynomial::normalised(&[0, 0]), None);
    }

    #[test]
    fn determinant_and_knot_check() {
        let trefoil = AlexanderPolynomial::normalised(&[1, -1, 1]).expect("non-zero");
        assert_eq!(trefoil.determinant(), 3);
        assert!(trefoil.is_knot_polynomial());
        let six_three = AlexanderPolynomial::normalised(&[1, -3, 5, -3, 1]).expect("non-zero");
        assert_eq!(six_three.determinant(), 13);
        let not_symmetric = AlexanderPolynomial::normalised(&[1, -2, 2]).expect("non-zero");
        assert!(!not_symmetric.is_knot_polynomial());
        let wrong_unit = AlexanderPolynomial::normalised(&[1, -1, 3, -1, 1]).expect("non-zero");
        assert!(!wrong_unit.is_knot_polynomial());
    }

    #[test]
    fn display_and_order() {
        let fig8 = AlexanderPolynomial::normalised(&[1, -3, 1]).expect("non-zero");
        assert_eq!(fig8.to_string(), "t^2 - 3t + 1");
        assert_eq!(AlexanderPolynomial::unknot().to_string(), "1");
        assert!(AlexanderPolynomial::unknot() < fig8);
        let trefoil = AlexanderPolynomial::normalised(&[1, -1, 1]).expect("non-zero");
        assert!(fig8 < trefoil);
    }
}
