//! The Alexander matrix of a knot diagram and its exact determinant.
//!
//! Walking along the knot, the diagram's crossings cut the curve at every under-pass into
//! c arcs (c = number of crossings; arc k runs from the k-th under-pass to the next). The
//! Wirtinger relation of a crossing whose under-strand runs from arc i into arc j below the
//! over-arc o, abelianised by Fox calculus (every meridian ↦ t), gives the matrix row
//!
//! * positive crossing: `1 − t` in column o, `t` in column i, `−1` in column j;
//! * negative crossing: `1 − t` in column o, `−1` in column i, `t` in column j
//!
//! (entries add up when columns coincide, e.g. at a kink). Deleting any one row and column
//! leaves the (c − 1)×(c − 1) matrix A + tB whose determinant is ±tᵏΔ(t) — computed exactly
//! by [`pencil_determinant`] and normalised by [`AlexanderPolynomial::normalised`]. Its
//! degree is at most c − 1.

use crate::AlexanderPolynomial;
use crate::determinant::pencil_determinant;

/// One crossing of a diagram: where the over- and the under-strand pass it (positions along
/// the closed curve, any increasing parametrisation) and its handedness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Crossing {
    /// Position of the over-strand.
    pub(crate) over: f64,
    /// Position of the under-strand.
    pub(crate) under: f64,
    /// Sign of the crossing, ((over direction) × (under direction)) · (towards viewer) > 0.
    pub(crate) positive: bool,
}

/// Writes into `code` the rows of the diagram's Alexander matrix: for each crossing, in the
/// order given, its over-arc, incoming and outgoing under-arc and 1 if it is positive (0 if
/// not). Diagrams with fewer than 2 crossings (unknots) have the empty code. The code
/// determines the matrix, hence the polynomial ([`code_polynomial`]).
pub(crate) fn arc_code(crossings: &[Crossing], code: &mut Vec<usize>) {
    code.clear();
    if crossings.len() < 2 {
        return;
    }
    for (crossing, arc) in crossings.iter().zip(arcs(crossings)) {
        code.extend([arc.over, arc.incoming, arc.outgoing, usize::from(crossing.positive)]);
    }
}

/// The Alexander polynomial of the diagram with this [`arc_code`] (positions of the
/// crossings all distinct), or `None` if the determinant fails
/// [`AlexanderPolynomial::is_knot_polynomial`] — which happens only if a coefficient exceeds
/// the exact range of the modular determinant.
pub(crate) fn code_polynomial(code: &[usize]) -> Option<AlexanderPolynomial> {
    let count = code.len() / 4;
    if count < 2 {
        return Some(AlexanderPolynomial::unknot());
    }
    let m = count - 1;
    let (mut a, mut b) = (vec![0i64; m * m], vec![0i64; m * m]);
    let mut add = |row: usize, col: usize, constant: i64, linear: i64| {
        if row < m && col < m {
            a[row * m + col] += constant;
            b[row * m + col] += linear;
        }
    };
    for (row, crossing) in code.chunks_exact(4).enumerate() {
        let &[over, incoming, outgoing, positive] = crossing else { continue };
        add(row, over, 1, -1);
        if positive == 1 {
            add(row, incoming, 0, 1);
            add(row, outgoing, -1, 0);
        } else {
            add(row, incoming, -1, 0);
            add(row, outgoing, 0, 1);
        }
    }
    let polynomial = AlexanderPolynomial::normalised(&pencil_determinant(&a, &b, m))?;
    polynomial.is_knot_polynomial().then_some(polynomial)
}

/// The arcs meeting at one crossing.
#[derive(Debug, Clone, Copy, Default)]
struct CrossingArcs {
    /// Arc passing over the crossing.
    over: usize,
    /// Arc ending at the crossing's under-pass.
    incoming: usize,
    /// Arc starting at the crossing's under-pass.
    outgoing: usize,
}

/// Labels the arcs met at every crossing: arc k starts at the k-th under-pass in curve
/// order; the stretch before the first under-pass belongs to the last arc, which wraps
/// around.
fn arcs(crossings: &[Crossing]) -> Vec<CrossingArcs> {
    let mut passes: Vec<(f64, usize, bool)> = crossings
        .iter()
        .enumerate()
        .flat_map(|(index, c)| [(c.over, index, false), (c.under, index, true)])
        .collect();
    passes.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut arcs = vec![CrossingArcs::default(); crossings.len()];
    let (mut current, mut next) = (crossings.len() - 1, 0);
    for (_, index, under) in passes {
        if under {
            arcs[index].incoming = current;
            current = next;
            arcs[index].outgoing = current;
            next += 1;
        } else {
            arcs[index].over = current;
        }
    }
    arcs
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Crossings from a Gauss code: (over position, under position, sign) per crossing.
    fn diagram(code: &[(f64, f64, bool)]) -> Vec<Crossing> {
        code.iter().map(|&(over, under, positive)| Crossing { over, under, positive }).collect()
    }

    /// The polynomial of the diagram with these crossings.
    fn diagram_polynomial(crossings: &[Crossing]) -> Option<AlexanderPolynomial> {
        let mut code = Vec::new();
        arc_code(crossings, &mut code);
        code_polynomial(&code)
    }

    #[test]
    fn standard_diagrams_give_their_polynomials() {
        // Trefoil: O1 U2 O3 U1 O2 U3, all crossings of one sign.
        let trefoil = diagram(&[(0.0, 3.0, true), (4.0, 1.0, true), (2.0, 5.0, true)]);
        let polynomial = diagram_polynomial(&trefoil).expect("knot polynomial");
        assert_eq!(polynomial.coefficients(), &[1, -1, 1]);
        // Figure-eight: O1 U2 O3 U4 O2 U1 O4 U3, signs − − + +.
        let figure_eight =
            diagram(&[(0.0, 5.0, false), (4.0, 1.0, false), (2.0, 7.0, true), (6.0, 3.0, true)]);
        let polynomial = diagram_polynomial(&figure_eight).expect("knot polynomial");
        assert_eq!(polynomial.coefficients(), &[1, -3, 1]);
    }

    #[test]
    fn kinks_and_empty_diagrams_are_unknots() {
        assert_eq!(diagram_polynomial(&[]), Some(AlexanderPolynomial::unknot()));
        let kinks = diagram(&[(0.0, 1.0, true), (2.0, 3.0, false), (5.0, 4.0, true)]);
        assert_eq!(diagram_polynomial(&kinks), Some(AlexanderPolynomial::unknot()));
    }
}
