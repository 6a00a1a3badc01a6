//! Obstacles as a scenario writes them (docs/physics.md, "Obstacles"): rigid planes, spheres
//! and cylinders posed in space, in cm.

use hagfish_geometry::{GeometryError, Obstacle};
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
}

impl ObstacleSpec {
    /// The obstacle, its numbers checked.
    pub fn to_obstacle(&self) -> Result<Obstacle, GeometryError> {
        match *self {
            ObstacleSpec::Plane { point, normal } => Obstacle::plane(point.into(), normal.into()),
            ObstacleSpec::Sphere { centre, radius } => Obstacle::sphere(centre.into(), radius),
            ObstacleSpec::Cylinder { point, axis, radius, half_length } => {
                Obstacle::cylinder(point.into(), axis.into(), radius, half_length)
            }
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
        let Ok(Obstacle::Cylinder { axis, half_length: None, .. }) = cylinder.to_obstacle() else {
            panic!("an infinite cylinder: {cylinder:?}")
        };
        assert_eq!(axis, glam::DVec3::Z, "the axis is normalised");
        let plane = ObstacleSpec::Plane { point: [0.0; 3], normal: [0.0; 3] };
        assert!(plane.to_obstacle().is_err(), "a zero normal");
        let sphere = ObstacleSpec::Sphere { centre: [0.0; 3], radius: -1.0 };
        assert!(sphere.to_obstacle().is_err(), "a negative radius");
    }
}
