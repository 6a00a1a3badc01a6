//! An obstacle turning about an axis of its symmetry: a roller (a cylinder about its own
//! axis), a ball (a sphere about any axis through its centre) or a turntable (a plane about its
//! normal). The turn leaves the shape where it is, so contacts are detected as for a still
//! obstacle; it moves the surface, at the point s with velocity ω × (s − p), ω = rate · axis and
//! p the obstacle's reference point (the cylinder's axis point, the sphere's centre, the
//! plane's point), which the contact rows take as the surface's velocity, as a path's.

use glam::DVec3;

use crate::error::GeometryError;
use crate::obstacle::Obstacle;

/// Largest |sin| of the angle between a spin axis and the shape's axis of symmetry (a
/// cylinder's axis, a plane's normal): parallel up to the rounding of a normalised input.
const PARALLEL_SINE: f64 = 1e-9;

/// A constant turn of an obstacle about an axis of its symmetry through its reference point
/// (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spin {
    /// The angular velocity ω = rate · axis (rad/s).
    angular_velocity: DVec3,
}

impl Spin {
    /// A turn of `shape` at `rate` rad/s (right-handed) about `axis` (normalised here), which
    /// must be an axis of the shape's symmetry: any for a sphere, the axis of a cylinder, the
    /// normal of a plane (either sense).
    pub fn new(shape: &Obstacle, axis: DVec3, rate: f64) -> Result<Self, GeometryError> {
        GeometryError::require_option(rate.is_finite(), "spin rate", "finite", rate)?;
        let axis = axis.try_normalize().ok_or(GeometryError::InvalidOption {
            name: "spin axis",
            requirement: "finite and non-zero",
            value: axis.length(),
        })?;
        let symmetry = match *shape {
            Obstacle::Sphere { .. } => None,
            Obstacle::Cylinder { axis, .. } => Some(axis),
            Obstacle::Plane { normal, .. } => Some(normal),
        };
        if let Some(symmetry) = symmetry {
            let sine = axis.cross(symmetry).length();
            GeometryError::require_option(
                sine <= PARALLEL_SINE,
                "spin axis",
                "an axis of the shape's symmetry (a cylinder's own axis, a plane's normal); \
                 sine of the angle to it",
                sine,
            )?;
        }
        Ok(Self { angular_velocity: rate * axis })
    }

    /// The angular velocity ω (rad/s).
    pub fn angular_velocity(&self) -> DVec3 {
        self.angular_velocity
    }

    /// The velocity (cm/s) of the surface point `surface` of an obstacle whose reference point
    /// is at `reference`: ω × (s − p).
    pub fn surface_velocity(&self, reference: DVec3, surface: DVec3) -> DVec3 {
        self.angular_velocity.cross(surface - reference)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turn_moves_the_surface_at_omega_cross_r_about_the_reference_point() {
        let roller =
            Obstacle::cylinder(DVec3::new(1.0, 0.0, 0.0), DVec3::Z, 2.0, None).expect("a cylinder");
        let spin = Spin::new(&roller, DVec3::new(0.0, 0.0, -3.0), 0.5).expect("its own axis");
        assert_eq!(spin.angular_velocity(), DVec3::new(0.0, 0.0, -0.5));
        // The top of the roller moves along +x at ωR = 1 cm/s when turning clockwise about z.
        let top = DVec3::new(1.0, 2.0, 7.0);
        let velocity = spin.surface_velocity(DVec3::new(1.0, 0.0, 0.0), top);
        assert!((velocity - DVec3::X).length() < 1e-15, "{velocity}");
        let ball = Obstacle::sphere(DVec3::ZERO, 1.0).expect("a sphere");
        assert!(Spin::new(&ball, DVec3::new(1.0, 1.0, 0.0), 2.0).is_ok(), "any axis of a ball");
        let table = Obstacle::plane(DVec3::ZERO, DVec3::Y).expect("a plane");
        assert!(Spin::new(&table, -DVec3::Y, 1.0).is_ok(), "about its normal, either sense");
    }

    #[test]
    fn a_turn_that_would_move_the_shape_or_is_not_a_number_is_refused() {
        let roller = Obstacle::cylinder(DVec3::ZERO, DVec3::Z, 2.0, Some(1.0)).expect("cylinder");
        assert!(Spin::new(&roller, DVec3::X, 1.0).is_err(), "across a cylinder");
        assert!(Spin::new(&roller, DVec3::new(0.0, 1e-6, 1.0), 1.0).is_err(), "tilted");
        let table = Obstacle::plane(DVec3::ZERO, DVec3::Y).expect("a plane");
        assert!(Spin::new(&table, DVec3::X, 1.0).is_err(), "in the plane");
        assert!(Spin::new(&table, DVec3::ZERO, 1.0).is_err(), "no axis");
        assert!(Spin::new(&table, DVec3::Y, f64::NAN).is_err(), "no rate");
    }
}
