//! An obstacle turning at a constant rate about an axis through its reference point p (the
//! cylinder's axis point, the sphere's centre, the plane's point). About an axis of its
//! symmetry — a roller (a cylinder about its own axis), a ball (a sphere about any axis through
//! its centre), a turntable (a plane about its normal) — the turn leaves the shape where it is,
//! so contacts are detected as for a still obstacle (bit for bit); about any other axis the
//! shape turns with it, by R(t) = exp(t ω×) about p (a plane tilting about a line in it, a
//! cylinder swinging about a diameter). Either way the surface point s moves at ω × (s − p),
//! ω = rate · axis, which the contact rows take as the surface's velocity, as a path's. A turn
//! may stop at a time T ([`Spin::until`]): from then on the obstacle holds the pose R(T) and
//! its surface is still (a plane tilted to an angle and held there).

use glam::{DQuat, DVec3};

use crate::error::GeometryError;
use crate::obstacle::Obstacle;

/// Largest |sin| of the angle between a spin axis and the shape's axis of symmetry (a
/// cylinder's axis, a plane's normal) for the turn to count as about it: parallel up to the
/// rounding of a normalised input.
const PARALLEL_SINE: f64 = 1e-9;

/// A constant turn of an obstacle about an axis through its reference point (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spin {
    /// The angular velocity ω = rate · axis (rad/s).
    angular_velocity: DVec3,
    /// Whether the turn moves the shape: its axis is not one of the shape's symmetry.
    turns_shape: bool,
    /// When the turn stops (s; infinite for one that never does).
    stop: f64,
}

impl Spin {
    /// A turn of `shape` at `rate` rad/s (right-handed) about `axis` (normalised here) through
    /// its reference point.
    ///
    /// # Errors
    /// [`GeometryError::InvalidOption`] if the rate is not finite or the axis is zero or not
    /// finite.
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
        let turns_shape = symmetry.is_some_and(|s| axis.cross(s).length() > PARALLEL_SINE);
        Ok(Self { angular_velocity: rate * axis, turns_shape, stop: f64::INFINITY })
    }

    /// The same turn, stopped at time `stop` (s, finite and ≥ 0): the pose R(T) is held after.
    ///
    /// # Errors
    /// [`GeometryError::InvalidOption`] if `stop` is negative or not finite.
    pub fn until(self, stop: f64) -> Result<Self, GeometryError> {
        GeometryError::require_non_negative(&[("spin stop time", stop)])?;
        Ok(Self { stop, ..self })
    }

    /// Whether the turn moves the shape (its axis is not one of the shape's symmetry), so that
    /// the obstacle at time t is the shape turned by [`Spin::rotation`].
    pub fn turns_shape(&self) -> bool {
        self.turns_shape
    }

    /// The rotation R(t) = exp(min(t, T) ω×) the turn has made by time `t` (s).
    pub fn rotation(&self, t: f64) -> DQuat {
        DQuat::from_scaled_axis(self.angular_velocity * t.min(self.stop))
    }

    /// The angular velocity ω while the turn lasts (rad/s).
    pub fn angular_velocity(&self) -> DVec3 {
        self.angular_velocity
    }

    /// The velocity (cm/s) at time `t` of the surface point `surface` of an obstacle whose
    /// reference point is at `reference`: ω × (s − p) before the stop, zero from it on.
    pub fn surface_velocity(&self, t: f64, reference: DVec3, surface: DVec3) -> DVec3 {
        match t < self.stop {
            true => self.angular_velocity.cross(surface - reference),
            false => DVec3::ZERO,
        }
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
        let velocity = spin.surface_velocity(0.0, DVec3::new(1.0, 0.0, 0.0), top);
        assert!((velocity - DVec3::X).length() < 1e-15, "{velocity}");
        let ball = Obstacle::sphere(DVec3::ZERO, 1.0).expect("a sphere");
        assert!(Spin::new(&ball, DVec3::new(1.0, 1.0, 0.0), 2.0).is_ok(), "any axis of a ball");
        let table = Obstacle::plane(DVec3::ZERO, DVec3::Y).expect("a plane");
        assert!(Spin::new(&table, -DVec3::Y, 1.0).is_ok(), "about its normal, either sense");
    }

    #[test]
    fn a_turn_about_another_axis_turns_the_shape_and_bad_numbers_are_refused() {
        let roller = Obstacle::cylinder(DVec3::ZERO, DVec3::Z, 2.0, Some(1.0)).expect("cylinder");
        assert!(!Spin::new(&roller, -DVec3::Z, 1.0).expect("its own axis").turns_shape());
        assert!(Spin::new(&roller, DVec3::X, 1.0).expect("across it").turns_shape());
        let tilted = Spin::new(&roller, DVec3::new(0.0, 1e-6, 1.0), 1.0).expect("tilted");
        assert!(tilted.turns_shape());
        let table = Obstacle::plane(DVec3::ZERO, DVec3::Y).expect("a plane");
        let tilting = Spin::new(&table, DVec3::X, 0.5).expect("about a line in it");
        assert!(tilting.turns_shape());
        let turned = tilting.rotation(1.0) * DVec3::Y;
        assert!((turned - DVec3::new(0.0, 0.5_f64.cos(), 0.5_f64.sin())).length() < 1e-15);
        let ball = Obstacle::sphere(DVec3::ZERO, 1.0).expect("a sphere");
        assert!(!Spin::new(&ball, DVec3::ONE, 1.0).expect("any axis").turns_shape());
        assert!(Spin::new(&table, DVec3::ZERO, 1.0).is_err(), "no axis");
        assert!(Spin::new(&table, DVec3::Y, f64::NAN).is_err(), "no rate");
        assert!(Spin::new(&table, DVec3::splat(f64::INFINITY), 1.0).is_err(), "no axis");
    }

    #[test]
    fn a_turn_that_stops_holds_its_last_pose_and_its_surface_is_still() {
        let table = Obstacle::plane(DVec3::ZERO, DVec3::Y).expect("a plane");
        let tilting = Spin::new(&table, DVec3::X, 0.5).expect("a tilt");
        let held = tilting.until(2.0).expect("a stop");
        assert_eq!(held.rotation(1.0), tilting.rotation(1.0), "the same turn before the stop");
        assert_eq!(held.rotation(7.0), tilting.rotation(2.0), "the pose at the stop after it");
        let point = DVec3::new(0.0, 0.0, 3.0);
        assert_eq!(held.surface_velocity(1.9, DVec3::ZERO, point), DVec3::new(0.0, -1.5, 0.0));
        assert_eq!(held.surface_velocity(2.0, DVec3::ZERO, point), DVec3::ZERO);
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            assert!(tilting.until(bad).is_err(), "{bad}");
        }
    }
}
