//! The Alexander polynomials of the diagrams already met.
//!
//! A vote meets the same diagram (the same [`arc_code`]) along many directions, and the
//! frames of a run meet the same few thousand diagrams over and over (≈ 90 % of the
//! determinants of the thesis run repeat one computed before). The polynomial is a function
//! of the code alone, so a remembered one is exactly the one that would be computed.

use std::collections::HashMap;

use crate::AlexanderPolynomial;
use crate::alexander::{Crossing, arc_code, code_polynomial};

/// Diagrams remembered before the memo starts afresh (bounds its memory on long runs).
const CAPACITY: usize = 1 << 14;

/// Polynomials (or `None`, see [`code_polynomial`]) by the arc code of their diagram.
#[derive(Debug, Default)]
pub(crate) struct PolynomialMemo {
    known: HashMap<Vec<usize>, Option<AlexanderPolynomial>>,
    code: Vec<usize>,
}

impl PolynomialMemo {
    /// The polynomial of the diagram with these crossings, as [`code_polynomial`] gives it.
    pub(crate) fn polynomial(&mut self, crossings: &[Crossing]) -> Option<AlexanderPolynomial> {
        arc_code(crossings, &mut self.code);
        if let Some(known) = self.known.get(self.code.as_slice()) {
            return known.clone();
        }
        let polynomial = code_polynomial(&self.code);
        if self.known.len() >= CAPACITY {
            self.known.clear();
        }
        self.known.insert(self.code.clone(), polynomial.clone());
        polynomial
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_remembered_diagram_gives_the_computed_polynomial() {
        // Trefoil: O1 U2 O3 U1 O2 U3, all crossings positive.
        let trefoil = [(0.0, 3.0), (4.0, 1.0), (2.0, 5.0)].map(|(over, under)| Crossing {
            over,
            under,
            positive: true,
        });
        let mut memo = PolynomialMemo::default();
        let first = memo.polynomial(&trefoil);
        assert_eq!(first.as_ref().map(AlexanderPolynomial::coefficients), Some(&[1, -1, 1][..]));
        assert_eq!(memo.polynomial(&trefoil), first);
        assert_eq!(memo.known.len(), 1);
        assert_eq!(memo.polynomial(&trefoil[..1]), Some(AlexanderPolynomial::unknot()));
    }
}
