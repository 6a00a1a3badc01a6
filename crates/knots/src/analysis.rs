//! Entry points: the knot type of an open curve and the polynomial of a closed one.

use glam::DVec3;

use crate::closure::NormalisedCurve;
use crate::extent::{knotted_extent, midpoint_arc_length};
use crate::vote::{
    PROJECTION_ATTEMPTS, Workspace, mean_writhe, no_polynomial, polygon_polynomial, vote,
};
use crate::{AlexanderPolynomial, KnotError, KnotOptions, KnotReport, KnotType};

/// Minimum number of points of an open curve (3 edges; a knot needs more, but fewer points
/// are rejected as input errors rather than reported as unknots).
pub const MIN_OPEN_POINTS: usize = 4;

/// Knot type of the open polygonal curve `points` (e.g. the body centres, in cm, head to
/// tail): the majority over [`KnotOptions::directions`] closures at infinity of the
/// Alexander polynomial, optionally with the knotted sub-arc.
///
/// Independent of position, orientation and units (the curve is normalised first), and
/// deterministic. To analyse many curves, [`KnotAnalyser::analyse`] gives the same reports
/// faster.
///
/// # Errors
/// [`KnotError::InvalidOption`] for a zero direction count, [`KnotError::TooFewPoints`] for
/// fewer than [`MIN_OPEN_POINTS`] points, [`KnotError::NonFinitePoint`],
/// [`KnotError::DegenerateExtent`] if all points coincide, and
/// [`KnotError::NoGenericProjection`] if the curve passes through itself so that no closure
/// could be evaluated.
pub fn analyse_knot(points: &[DVec3], options: &KnotOptions) -> Result<KnotReport, KnotError> {
    KnotAnalyser::default().analyse(points, options)
}

/// The knot analysis of [`analyse_knot`], keeping its buffers and the polynomials of the
/// diagrams it has met from one curve to the next: the frames of a run meet the same few
/// diagrams again and again. Its reports are those of [`analyse_knot`], bit for bit.
#[derive(Debug, Default)]
pub struct KnotAnalyser {
    workspace: Workspace,
}

impl KnotAnalyser {
    /// [`analyse_knot`]`(points, options)`.
    ///
    /// # Errors
    /// Those of [`analyse_knot`].
    pub fn analyse(
        &mut self,
        points: &[DVec3],
        options: &KnotOptions,
    ) -> Result<KnotReport, KnotError> {
        options.validate()?;
        KnotError::check_points(points, MIN_OPEN_POINTS)?;
        let curve = NormalisedCurve::new(points)?;
        let winner = vote(&curve, options.directions, &mut self.workspace)
            .ok_or_else(|| no_polynomial(&self.workspace, options.directions))?;
        let knot = KnotType::from_polynomial(&winner.polynomial);
        let extent = (options.extent && knot != KnotType::Unknot).then(|| {
            knotted_extent(
                points,
                &winner.polynomial,
                options.extent_directions,
                &mut self.workspace,
            )
        });
        let writhe = extent.and_then(|(first, last)| {
            let core = NormalisedCurve::new(&points[first..=last]).ok()?;
            mean_writhe(&core, options.directions, &mut self.workspace)
        });
        Ok(KnotReport {
            knot,
            determinant: winner.polynomial.determinant(),
            polynomial: winner.polynomial,
            agreement: winner.agreement,
            directions_evaluated: winner.evaluated,
            extent,
            position: extent.map(|(first, last)| midpoint_arc_length(points, first, last)),
            writhe,
        })
    }
}

/// Alexander polynomial of the closed polygon `vertices` (the last vertex joins the first;
/// repeating the first vertex at the end is allowed). Useful for closed curves and to check
/// test knots before cutting them open.
///
/// # Errors
/// [`KnotError::TooFewPoints`] for fewer than 3 vertices, [`KnotError::NonFinitePoint`],
/// [`KnotError::DegenerateExtent`], and [`KnotError::NoGenericProjection`] if the polygon
/// passes through itself.
pub fn closed_polygon_polynomial(vertices: &[DVec3]) -> Result<AlexanderPolynomial, KnotError> {
    KnotError::check_points(vertices, 3)?;
    let curve = NormalisedCurve::new(vertices)?;
    let mut workspace = Workspace::default();
    polygon_polynomial(curve.as_closed_polygon(), DVec3::Z, &mut workspace)
        .ok_or_else(|| no_polynomial(&workspace, PROJECTION_ATTEMPTS))
}
