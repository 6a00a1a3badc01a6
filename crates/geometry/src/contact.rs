//! Self-contact records: where the centreline tube comes close to itself.

use glam::DVec3;

use crate::centreline::Centreline;
use crate::narrow_phase::NewtonStatus;
use crate::weights::SplineWeights;

/// Distance (cm) under which the closest points are treated as coincident and the normal
/// is taken from the tangents instead of from Δ.
const COINCIDENT_DISTANCE: f64 = 1e-12;

/// One self contact between two points of the centreline tube.
///
/// Point a is the anterior one (u_a < u_b), as the thigmotaxis rows and the first/last
/// contact ordering require (docs/physics.md, "Thigmotaxis": first and last contact by anterior parameter). The solver builds the non-penetration row
/// nᵀ(P(u_b) − P(u_a)) q̇ ≥ b from `normal` and the two weight sets, and the thigmotaxis
/// rows from the tangents.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfContact {
    /// Spline parameter of the anterior point.
    pub u_a: f64,
    /// Spline parameter of the posterior point (u_b > u_a).
    pub u_b: f64,
    /// x(u_a) (cm).
    pub point_a: DVec3,
    /// x(u_b) (cm).
    pub point_b: DVec3,
    /// Unit normal from a to b: n = (x_b − x_a)/|x_b − x_a|. When the two points coincide
    /// it is the unit t_a × t_b (or any unit vector normal to t_a if they are parallel,
    /// or +x if the centreline is degenerate there).
    pub normal: DVec3,
    /// |x_b − x_a| (cm).
    pub distance: f64,
    /// Signed tube gap d = |x_b − x_a| − (r(u_a) + r(u_b)) (cm); negative when the tubes
    /// overlap.
    pub gap: f64,
    /// Unit tangent x′/|x′| at a, pointing tail-ward (increasing u).
    pub tangent_a: DVec3,
    /// Unit tangent x′/|x′| at b, pointing tail-ward (increasing u).
    pub tangent_b: DVec3,
    /// Bodies and weights whose blend is x(u_a).
    pub weights_a: SplineWeights,
    /// Bodies and weights whose blend is x(u_b).
    pub weights_b: SplineWeights,
    /// Outcome of the closest-point search that produced this record.
    pub status: NewtonStatus,
}

impl SelfContact {
    /// Builds the record between the points u_a < u_b of `centreline`, found by a search
    /// that ended with `status`.
    pub(crate) fn new(
        centreline: &Centreline,
        u_a: f64,
        u_b: f64,
        status: NewtonStatus,
    ) -> SelfContact {
        let point_a = centreline.point(u_a);
        let point_b = centreline.point(u_b);
        let tangent_a = centreline.unit_tangent(u_a);
        let tangent_b = centreline.unit_tangent(u_b);
        let delta = point_b - point_a;
        let distance = delta.length();
        let normal = if distance > COINCIDENT_DISTANCE {
            delta / distance
        } else {
            tangent_a
                .cross(tangent_b)
                .try_normalize()
                .or_else(|| tangent_a.try_normalize().map(DVec3::any_orthonormal_vector))
                .unwrap_or(DVec3::X)
        };
        SelfContact {
            u_a,
            u_b,
            point_a,
            point_b,
            normal,
            distance,
            gap: distance - (centreline.radius(u_a) + centreline.radius(u_b)),
            tangent_a,
            tangent_b,
            weights_a: centreline.weights(u_a),
            weights_b: centreline.weights(u_b),
            status,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coincident_points_take_the_normal_from_the_tangents() {
        // The chain runs along +x through (2, 0, 0) = c₂, then comes back along +y through
        // the same point as c₈, so x(2) = x(8) exactly.
        let centres = [
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (3.0, 0.0),
            (4.0, 0.0),
            (4.0, -1.0),
            (3.0, -1.5),
            (2.0, -1.0),
            (2.0, 0.0),
            (2.0, 1.0),
        ]
        .map(|(x, y)| DVec3::new(x, y, 0.0));
        let line = Centreline::new(&centres, &[0.3; 10]).expect("valid");
        let contact = SelfContact::new(&line, 2.0, 8.0, NewtonStatus::Converged);
        assert_eq!(contact.distance, 0.0);
        assert!((contact.gap + 0.6).abs() < 1e-15);
        assert!(contact.tangent_a.distance(DVec3::X) < 1e-12);
        assert!(contact.tangent_b.distance(DVec3::Y) < 1e-12);
        assert!(contact.normal.distance(DVec3::Z) < 1e-12, "t_a × t_b");
        assert_eq!((contact.weights_a.len, contact.weights_a.bodies[1]), (4, 2));
    }
}
