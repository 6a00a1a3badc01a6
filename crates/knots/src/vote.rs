//! The majority vote over closure directions.

use glam::DVec3;

use crate::AlexanderPolynomial;
use crate::KnotError;
use crate::alexander::Crossing;
use crate::closure::NormalisedCurve;
use crate::directions::{fibonacci_sphere, projection_direction};
use crate::memo::PolynomialMemo;
use crate::projection::{MAX_CROSSINGS, Projector};

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

/// The error for a curve that gave no polynomial in `directions` directions: too tangled if a
/// projection went over [`crate::MAX_CROSSINGS`], otherwise not generic in any.
pub(crate) fn no_polynomial(workspace: &Workspace, directions: usize) -> KnotError {
    if workspace.projector.over_limit {
        KnotError::TooManyCrossings { max: MAX_CROSSINGS }
    } else {
        KnotError::NoGenericProjection { directions }
    }
}

/// What votes keep from one closure to the next: the buffers of the projection and the
/// polynomials of the diagrams met so far.
#[derive(Debug, Default)]
pub(crate) struct Workspace {
    polygon: Vec<DVec3>,
    projector: Projector,
    crossings: Vec<Crossing>,
    memo: PolynomialMemo,
}

/// Alexander polynomial of the closed `polygon`, from the first generic view among
/// [`projection_direction`]`(axis, 0..PROJECTION_ATTEMPTS)`; `polygon` is not one of
/// `workspace`'s buffers.
pub(crate) fn polygon_polynomial(
    polygon: &[DVec3],
    axis: DVec3,
    workspace: &mut Workspace,
) -> Option<AlexanderPolynomial> {
    let Workspace { projector, crossings, memo, .. } = workspace;
    (0..PROJECTION_ATTEMPTS).find_map(|attempt| {
        let generic = projector.crossings(polygon, projection_direction(axis, attempt), crossings);
        if generic { memo.polynomial(crossings) } else { None }
    })
}

/// The mean writhe of the closures of `curve` along `directions` Fibonacci-sphere directions:
/// the sum of the crossing signs of each closure's first generic projection, averaged over
/// the closures that had one (`None` if none did). Averaged over directions, a diagram's
/// crossing-sign sum is the writhe of the closed curve; for a knotted core its sign tells a
/// knot from its mirror image, which the Alexander polynomial cannot (a right-handed
/// trefoil's writhe is about +3, a left-handed one's about −3).
pub(crate) fn mean_writhe(
    curve: &NormalisedCurve,
    directions: usize,
    workspace: &mut Workspace,
) -> Option<f64> {
    let mut polygon = std::mem::take(&mut workspace.polygon);
    let (mut sum, mut evaluated) = (0i64, 0usize);
    workspace.projector.reset_limit();
    for direction in fibonacci_sphere(directions) {
        curve.close(direction, &mut polygon);
        let Workspace { projector, crossings, .. } = workspace;
        let generic = (0..PROJECTION_ATTEMPTS).any(|attempt| {
            projector.crossings(&polygon, projection_direction(direction, attempt), crossings)
        });
        if generic {
            evaluated += 1;
            sum += crossings.iter().map(|c| if c.positive { 1 } else { -1 }).sum::<i64>();
        }
    }
    workspace.polygon = polygon;
    (evaluated > 0).then(|| sum as f64 / evaluated as f64)
}

/// The polynomials counted so far in a vote.
#[derive(Debug, Default)]
struct Tally {
    counts: Vec<(AlexanderPolynomial, usize)>,
    evaluated: usize,
}

impl Tally {
    /// The most frequent polynomial (ties to the simpler), or `None` if nothing was counted.
    fn winner(self) -> Option<Vote> {
        let evaluated = self.evaluated;
        let (polynomial, count) =
            self.counts.into_iter().max_by(|(p, m), (q, n)| m.cmp(n).then_with(|| q.cmp(p)))?;
        Some(Vote { polynomial, agreement: count as f64 / evaluated as f64, evaluated })
    }

    /// Whether `remaining` more directions can no longer change whether `target` wins: it
    /// leads every other polynomial by more than `remaining`, or one leads it by more.
    fn settles(&self, target: &AlexanderPolynomial, remaining: usize) -> bool {
        let count = |wanted: bool| {
            self.counts.iter().filter(move |(p, _)| (p == target) == wanted).map(|(_, n)| *n)
        };
        let target_count = count(true).next().unwrap_or(0);
        let best_other = count(false).max().unwrap_or(0);
        target_count > best_other + remaining || best_other > target_count + remaining
    }
}

/// Closes `curve` along each of `directions` Fibonacci-sphere directions and counts each
/// closure's polynomial, stopping early once `settled(tally, directions left)`.
fn count(
    curve: &NormalisedCurve,
    directions: usize,
    workspace: &mut Workspace,
    settled: impl Fn(&Tally, usize) -> bool,
) -> Tally {
    let mut polygon = std::mem::take(&mut workspace.polygon);
    let mut tally = Tally::default();
    workspace.projector.reset_limit();
    for (k, direction) in fibonacci_sphere(directions).enumerate() {
        curve.close(direction, &mut polygon);
        if let Some(polynomial) = polygon_polynomial(&polygon, direction, workspace) {
            tally.evaluated += 1;
            match tally.counts.iter_mut().find(|(known, _)| *known == polynomial) {
                Some((_, count)) => *count += 1,
                None => tally.counts.push((polynomial, 1)),
            }
        }
        if settled(&tally, directions - k - 1) {
            break;
        }
    }
    workspace.polygon = polygon;
    tally
}

/// Closes `curve` along each of `directions` Fibonacci-sphere directions, computes each
/// closure's polynomial and returns the most frequent one; `None` if no direction produced a
/// polynomial.
pub(crate) fn vote(
    curve: &NormalisedCurve,
    directions: usize,
    workspace: &mut Workspace,
) -> Option<Vote> {
    count(curve, directions, workspace, |_, _| false).winner()
}

/// Whether [`vote`] would elect `target`, stopping as soon as the remaining directions
/// cannot change that.
pub(crate) fn elects(
    curve: &NormalisedCurve,
    directions: usize,
    target: &AlexanderPolynomial,
    workspace: &mut Workspace,
) -> bool {
    let tally = count(curve, directions, workspace, |tally, left| tally.settles(target, left));
    tally.winner().is_some_and(|winner| &winner.polynomial == target)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tally(counts: &[(&[i64], usize)]) -> Tally {
        let counts: Vec<(AlexanderPolynomial, usize)> = counts
            .iter()
            .filter_map(|&(c, n)| Some((AlexanderPolynomial::normalised(c)?, n)))
            .collect();
        let evaluated = counts.iter().map(|c| c.1).sum();
        Tally { counts, evaluated }
    }

    #[test]
    fn a_vote_is_settled_only_when_no_remaining_direction_can_change_it() {
        let trefoil = AlexanderPolynomial::normalised(&[1, -1, 1]).expect("non-zero");
        let votes = tally(&[(&[1, -1, 1], 9), (&[1], 2)]);
        assert!(votes.settles(&trefoil, 6), "9 > 2 + 6");
        assert!(!votes.settles(&trefoil, 7), "2 + 7 would tie");
        let unknot = AlexanderPolynomial::unknot();
        assert!(votes.settles(&unknot, 6), "the trefoil leads the unknot by 7");
        assert!(!votes.settles(&unknot, 7));
        assert!(!tally(&[]).settles(&trefoil, 1), "nothing counted yet");
    }
}
