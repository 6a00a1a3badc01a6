//! Deterministic closure and projection directions.

use glam::DVec3;

/// The golden angle π(3 − √5), the azimuth step of the Fibonacci sphere.
const GOLDEN_ANGLE: f64 = 2.399_963_229_728_653;

/// Angle between a closure direction and its projection (view) direction, rad. Far from 0
/// so the closure rays do not project to near-points, far from π/2 so they do not project to
/// near-parallel long lines over the whole drawing.
const PROJECTION_TILT: f64 = 1.0;

/// Azimuth of the first projection direction about the closure direction, rad; an arbitrary
/// "irrational" value so the view is not aligned with any axis the input may favour.
const PROJECTION_AZIMUTH: f64 = 0.737_123;

/// `count` quasi-uniform unit vectors on the sphere: the Fibonacci (golden-angle) spiral
/// dₖ = (√(1 − zₖ²) cos kφ, √(1 − zₖ²) sin kφ, zₖ), zₖ = 1 − (2k + 1)/count, φ the golden
/// angle. Deterministic, and each point represents an equal area of the sphere.
pub(crate) fn fibonacci_sphere(count: usize) -> impl Iterator<Item = DVec3> {
    (0..count).map(move |k| {
        let z = 1.0 - (2 * k + 1) as f64 / count as f64;
        let radius = (1.0 - z * z).max(0.0).sqrt();
        let (sin, cos) = (k as f64 * GOLDEN_ANGLE).sin_cos();
        DVec3::new(radius * cos, radius * sin, z)
    })
}

/// The `attempt`-th view direction for closure direction `closure` (unit): tilted by
/// [`PROJECTION_TILT`] from it, at azimuth [`PROJECTION_AZIMUTH`] + attempt·(golden angle)
/// about it, so successive attempts after a non-generic projection spread around the cone.
pub(crate) fn projection_direction(closure: DVec3, attempt: usize) -> DVec3 {
    let (u, w) = closure.any_orthonormal_pair();
    let (sin_azimuth, cos_azimuth) = (PROJECTION_AZIMUTH + attempt as f64 * GOLDEN_ANGLE).sin_cos();
    let (sin_tilt, cos_tilt) = PROJECTION_TILT.sin_cos();
    (cos_tilt * closure + sin_tilt * (cos_azimuth * u + sin_azimuth * w)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_are_unit_and_balanced() {
        let directions: Vec<DVec3> = fibonacci_sphere(64).collect();
        assert!(directions.iter().all(|d| (d.length() - 1.0).abs() < 1e-12));
        assert!(directions.iter().sum::<DVec3>().length() / 64.0 < 0.01);
        let view = projection_direction(directions[5], 3);
        assert!((view.dot(directions[5]) - PROJECTION_TILT.cos()).abs() < 1e-12);
    }
}
