//! Arithmetic in the prime field 𝔽ₚ, p = 2⁶¹ − 1, used for the exact determinant.
//!
//! A Mersenne prime keeps the reduction of a 122-bit product to two shifts and an add, and
//! leaves room for integer results up to (p − 1)/2 ≈ 1.15·10¹⁸ in magnitude to be recovered
//! exactly from their residue (see [`Residue::to_symmetric`]).

use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// The Mersenne prime p = 2⁶¹ − 1.
pub(crate) const MODULUS: u64 = (1 << 61) - 1;

/// An element of 𝔽ₚ, stored as its representative in `0..p`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Residue(u64);

impl Residue {
    /// The additive identity.
    pub(crate) const ZERO: Residue = Residue(0);
    /// The multiplicative identity.
    pub(crate) const ONE: Residue = Residue(1);

    /// The residue of an integer, `value mod p`.
    pub(crate) fn from_i64(value: i64) -> Self {
        // p < i64::MAX, so the cast of the modulus and of the non-negative result are exact.
        Residue(value.rem_euclid(MODULUS as i64) as u64)
    }

    /// The integer in `(−p/2, p/2]` congruent to this residue: the exact value of any
    /// integer result known to lie in that range.
    pub(crate) fn to_symmetric(self) -> i64 {
        if self.0 > MODULUS / 2 { self.0 as i64 - MODULUS as i64 } else { self.0 as i64 }
    }

    /// Whether this is zero.
    pub(crate) fn is_zero(self) -> bool {
        self.0 == 0
    }

    /// The multiplicative inverse a^(p−2) (Fermat), or `None` for zero. ±1, their own
    /// inverses and nearly every pivot of an Alexander matrix, are returned at once.
    pub(crate) fn inverse(self) -> Option<Self> {
        if self.is_zero() {
            return None;
        }
        if self == Residue::ONE || self == -Residue::ONE {
            return Some(self);
        }
        let (mut base, mut exponent, mut result) = (self, MODULUS - 2, Residue::ONE);
        while exponent > 0 {
            if exponent & 1 == 1 {
                result = result * base;
            }
            base = base * base;
            exponent >>= 1;
        }
        Some(result)
    }

    /// Σᵢ aᵢbᵢ with one reduction per 64 products (each product is below 2¹²², so 64 of
    /// them fit in a u128).
    pub(crate) fn dot(a: &[Residue], b: &[Residue]) -> Residue {
        a.chunks(64).zip(b.chunks(64)).fold(Residue::ZERO, |acc, (x, y)| {
            let sum = x.iter().zip(y).map(|(p, q)| u128::from(p.0) * u128::from(q.0)).sum();
            acc + Residue::reduce(sum)
        })
    }

    /// `value mod p` for any u128, using 2⁶¹ ≡ 1 (mod p): the 61-bit digits are added.
    fn reduce(value: u128) -> Residue {
        let digits =
            (value as u64 & MODULUS) + ((value >> 61) as u64 & MODULUS) + (value >> 122) as u64;
        let folded = (digits & MODULUS) + (digits >> 61);
        Residue(if folded >= MODULUS { folded - MODULUS } else { folded })
    }
}

impl Add for Residue {
    type Output = Residue;
    fn add(self, other: Residue) -> Residue {
        let sum = self.0 + other.0;
        Residue(if sum >= MODULUS { sum - MODULUS } else { sum })
    }
}

impl Sub for Residue {
    type Output = Residue;
    fn sub(self, other: Residue) -> Residue {
        Residue(if self.0 >= other.0 { self.0 - other.0 } else { self.0 + MODULUS - other.0 })
    }
}

impl Neg for Residue {
    type Output = Residue;
    fn neg(self) -> Residue {
        Residue::ZERO - self
    }
}

impl Mul for Residue {
    type Output = Residue;
    fn mul(self, other: Residue) -> Residue {
        Residue::reduce(u128::from(self.0) * u128::from(other.0))
    }
}

impl AddAssign for Residue {
    fn add_assign(&mut self, other: Residue) {
        *self = *self + other;
    }
}

impl SubAssign for Residue {
    fn sub_assign(&mut self, other: Residue) {
        *self = *self - other;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// p − 2 − k, a residue close to p.
    fn big_minus(k: i64) -> Residue {
        Residue::from_i64(MODULUS as i64 - 2 - k)
    }

    #[test]
    fn field_operations_match_integer_arithmetic() {
        let a = Residue::from_i64(-123_456_789);
        let b = Residue::from_i64(987_654_321);
        assert_eq!((a * b).to_symmetric(), -123_456_789 * 987_654_321);
        assert_eq!((a + b).to_symmetric(), -123_456_789 + 987_654_321);
        assert_eq!((-a).to_symmetric(), 123_456_789);
        let (x, y): (Vec<Residue>, Vec<Residue>) =
            (0..100).map(|k| (Residue::from_i64(MODULUS as i64 - 1 - k), big_minus(k))).unzip();
        let expected = x.iter().zip(&y).fold(Residue::ZERO, |acc, (&p, &q)| acc + p * q);
        assert_eq!(Residue::dot(&x, &y), expected);
        let inverse = a.inverse().expect("non-zero");
        assert_eq!(a * inverse, Residue::ONE);
        for unit in [Residue::ONE, -Residue::ONE] {
            assert_eq!(unit.inverse().map(|inverse| inverse * unit), Some(Residue::ONE));
        }
        assert_eq!(Residue::ZERO.inverse(), None);
        let big = Residue::from_i64(MODULUS as i64 - 1);
        assert_eq!((big * big).to_symmetric(), 1);
    }
}
