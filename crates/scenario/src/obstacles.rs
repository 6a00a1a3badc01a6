//! Obstacles as a scenario writes them (docs/physics.md, "Obstacles"): rigid planes, spheres
//! and cylinders posed in space, in cm, still or moving on a path.

use glam::DVec3;
use hagfish_geometry::{GeometryError, MovingObstacle, Obstacle, ObstaclePath, Spin};
use serde::{Deserialize, Serialize};

/// One obstacle of a scenario's `obstacles` list, e.g.
/// `Cylinder(point: (10.0, -3.0, 0.0), axis: (0.0, 0.0, 1.0), radius: 2.0)` (points and
/// directions are RON tuples).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ObstacleSpec {
    /// The half-space behind the plane through `point` (cm) with normal `normal` toward the
    /// free side.
    Plane {
        /// A point of the plane (cm).
        point: [f64; 3],
        /// The normal toward the free side (any length but zero).
        normal: [f64; 3],
    },
    /// A solid sphere.
    Sphere {
        /// Centre (cm).
        centre: [f64; 3],
        /// Radius (cm, > 0).
        radius: f64,
    },
    /// A solid circular cylinder about the axis through `point` along `axis`.
    Cylinder {
        /// A point of the axis, the middle of a finite cylinder (cm).
        point: [f64; 3],
        /// The axis direction (any length but zero).
        axis: [f64; 3],
        /// Radius (cm, > 0).
        radius: f64,
        /// Half of the length (cm, > 0); `None` (default) for an infinite cylinder.
        #[serde(default)]
        half_length: Option<f64>,
    },
    /// A still obstacle `shape` moved along `path`: (time s, offset cm) waypoints at
    /// increasing times, linear between them and held beyond the ends, e.g.
    /// `Moving(shape: Sphere(centre: (5.0, 3.0, 0.0), radius: 1.0), path: [(0.0, (0.0, 0.0,
    /// 0.0)), (10.0, (20.0, 0.0, 0.0))])` (2 cm/s along x for 10 s); and optionally turning
    /// about an axis through its reference point, e.g. a roller turning in place:
    /// `Moving(shape: Cylinder(…, axis: (0.0, 0.0, 1.0), …), path: [], spin: Some((axis:
    /// (0.0, 0.0, 1.0), rate_rad_per_s: 0.5)))`.
    Moving {
        /// The obstacle at offset zero (not itself a moving one).
        shape: Box<ObstacleSpec>,
        /// The waypoints (none: it stays where `shape` puts it).
        path: Vec<(f64, [f64; 3])>,
        /// Its turn (`None`, the default: it does not turn).
        #[serde(default)]
        spin: Option<SpinSpec>,
    },
}

/// A turn of an obstacle at a constant rate about an axis through its reference point (the
/// sphere's centre, the cylinder's axis point, the plane's point; `hagfish_geometry::Spin`):
/// about an axis of its symmetry (any for a sphere, its own axis for a cylinder, its normal
/// for a plane) only its surface moves; about another the shape turns too (a tilting plane).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpinSpec {
    /// The axis (any length but zero), right-handed with the rate.
    pub axis: [f64; 3],
    /// The angular speed (rad/s).
    pub rate_rad_per_s: f64,
    /// When the turn stops (s; `None`, the default: never): the obstacle holds the pose it has
    /// then, e.g. a plane tilted by rate · until_s and held.
    #[serde(default)]
    pub until_s: Option<f64>,
}

impl ObstacleSpec {
    /// The obstacle and its path (empty for a still one), its numbers checked.
    pub fn to_obstacle(&self) -> Result<MovingObstacle, GeometryError> {
        match self {
            ObstacleSpec::Moving { shape, path, spin } => {
                let waypoints = path.iter().map(|&(t, offset)| (t, DVec3::from(offset))).collect();
                let path = ObstaclePath::new(waypoints)?;
                let shape = shape.to_still_obstacle()?;
                let spin = spin
                    .map(|spin| {
                        let turn = Spin::new(&shape, spin.axis.into(), spin.rate_rad_per_s)?;
                        spin.until_s.map_or(Ok(turn), |stop| turn.until(stop))
                    })
                    .transpose()?;
                Ok(MovingObstacle { shape, path, spin })
            }
            still => still.to_still_obstacle().map(MovingObstacle::from),
        }
    }

    /// The plane, sphere or cylinder as posed; a `Moving` one is refused (the shape of a
    /// moving obstacle must be still).
    fn to_still_obstacle(&self) -> Result<Obstacle, GeometryError> {
        match *self {
            ObstacleSpec::Plane { point, normal } => Obstacle::plane(point.into(), normal.into()),
            ObstacleSpec::Sphere { centre, radius } => Obstacle::sphere(centre.into(), radius),
            ObstacleSpec::Cylinder { point, axis, radius, half_length } => {
                Obstacle::cylinder(point.into(), axis.into(), radius, half_length)
            }
            ObstacleSpec::Moving { .. } => Err(GeometryError::InvalidOption {
                name: "Moving.shape",
                requirement: "a plane, sphere or cylinder, not another Moving",
                value: f64::NAN,
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_become_their_obstacles_and_bad_numbers_are_refused() {
        let cylinder: ObstacleSpec =
            ron::from_str("Cylinder(point: (1.0, 2.0, 3.0), axis: (0.0, 0.0, 2.0), radius: 0.5)")
                .expect("a cylinder");
        let Ok(Obstacle::Cylinder { axis, half_length: None, .. }) =
            cylinder.to_obstacle().map(|o| o.shape)
        else {
            panic!("an infinite cylinder: {cylinder:?}")
        };
        assert_eq!(axis, glam::DVec3::Z, "the axis is normalised");
        let plane = ObstacleSpec::Plane { point: [0.0; 3], normal: [0.0; 3] };
        assert!(plane.to_obstacle().is_err(), "a zero normal");
        let sphere = ObstacleSpec::Sphere { centre: [0.0; 3], radius: -1.0 };
        assert!(sphere.to_obstacle().is_err(), "a negative radius");
        let moving: ObstacleSpec = ron::from_str(
            "Moving(shape: Sphere(centre: (5.0, 3.0, 0.0), radius: 1.0), \
             path: [(0.0, (0.0, 0.0, 0.0)), (10.0, (20.0, 0.0, 0.0))])",
        )
        .expect("a moving sphere");
        let on_path = moving.to_obstacle().expect("valid");
        assert_eq!(on_path.path.velocity(5.0), glam::DVec3::new(2.0, 0.0, 0.0));
        let backwards = "Moving(shape: Sphere(centre: (0.0, 0.0, 0.0), radius: 1.0), \
                         path: [(2.0, (0.0, 0.0, 0.0)), (1.0, (1.0, 0.0, 0.0))])";
        let backwards: ObstacleSpec = ron::from_str(backwards).expect("parses");
        assert!(backwards.to_obstacle().is_err(), "times must increase");
        let nested = ObstacleSpec::Moving { shape: Box::new(moving), path: Vec::new(), spin: None };
        assert!(nested.to_obstacle().is_err(), "a moving shape on a path");
        let roller = "Moving(shape: Cylinder(point: (0.0, 0.0, 0.0), axis: (0.0, 0.0, 1.0), \
                      radius: 2.0), path: [], spin: Some((axis: (0.0, 0.0, 2.0), \
                      rate_rad_per_s: 0.5)))";
        let roller: ObstacleSpec = ron::from_str(roller).expect("a turning roller");
        let spin = roller.to_obstacle().expect("valid").spin.expect("a spin");
        assert_eq!(spin.angular_velocity(), glam::DVec3::new(0.0, 0.0, 0.5));
        assert!(!spin.turns_shape(), "a roller turns in place");
        let ObstacleSpec::Moving { shape, path, .. } = roller else { unreachable!() };
        let swinging = Some(SpinSpec { axis: [1.0, 0.0, 0.0], rate_rad_per_s: 0.5, until_s: None });
        let across =
            ObstacleSpec::Moving { shape: shape.clone(), path: path.clone(), spin: swinging };
        let spin = across.to_obstacle().expect("valid").spin.expect("a spin");
        assert!(spin.turns_shape(), "a cylinder turning across its axis swings");
        let stalled = Some(SpinSpec { axis: [0.0; 3], rate_rad_per_s: 0.5, until_s: None });
        let no_axis = ObstacleSpec::Moving { shape, path, spin: stalled };
        assert!(no_axis.to_obstacle().is_err(), "a turn about no axis");
    }
}
