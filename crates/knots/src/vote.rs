//! The majority vote over closure directions.

use glam::DVec3;

use crate::AlexanderPolynomial;
use crate::alexander::diagram_polynomial;
use crate::closure::NormalisedCurve;
use crate::directions::{fibonacci_sphere, projection_direction};
use crate::projection::crossings;

/// Projection directions tried per closure before giving up on it (each fails only if the
/// polygon nearly passes through itself as seen along it).
pub(crate) const PROJECTION_ATTEMPTS: usize = 8;

/// The winner of a vote.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Vote {
    /// The most frequent polynomial (ties go to the simpler, see [`AlexanderPolynomial`]).
    pub(crate) polynomial: AlexanderPolynomial,
    /// Its share of the evaluated directions.
    pub(crate) agreement: f64,
    /// Number of directions that produced a polynomial.
    pub(crate) evaluated: usize,
}

/// Alexander polynomial of the closed `polygon`, from the first generic view among
/// [`projection_direction`]`(axis, 0..PROJECTION_ATTEMPTS)`.
pub(crate) fn polygon_polynomial(polygon: &[DVec3], axis: DVec3) -> Option<AlexanderPolynomial> {
    (0..PROJECTION_ATTEMPTS).find_map(|attempt| {
        diagram_polynomial(&crossings(polygon, projection_direction(axis, attempt))?)
    })
}

/// Closes `curve` along each of `directions` Fibonacci-sphere directions, computes each
/// closure's polynomial and returns the most frequent one; `None` if no direction produced a
/// polynomial.
pub(crate) fn vote(curve: &NormalisedCurve, directions: usize) -> Option<Vote> {
    let mut polygon = Vec::new();
    let mut tally: Vec<(AlexanderPolynomial, usize)> = Vec::new();
    let mut evaluated = 0;
    for direction in fibonacci_sphere(directions) {
        curve.close(direction, &mut polygon);
        let Some(polynomial) = polygon_polynomial(&polygon, direction) else {
            continue;
        };
        evaluated += 1;
        match tally.iter_mut().find(|(known, _)| *known == polynomial) {
            Some((_, count)) => *count += 1,
            None => tally.push((polynomial, 1)),
        }
    }
    let (polynomial, count) =
        tally.into_iter().max_by(|(p, m), (q, n)| m.cmp(n).then_with(|| q.cmp(p)))?;
    Some(Vote { polynomial, agreement: count as f64 / evaluated as f64, evaluated })
}
