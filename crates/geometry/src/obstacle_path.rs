//! Obstacles that move on a prescribed path: offsets from their pose at given times,
//! linear between them (so the obstacle moves at a constant velocity along each leg) and held
//! beyond the ends; it may also turn about an axis through its reference point
//! (`obstacle_spin.rs`). A moving obstacle's contacts carry its surface's velocity v_o, and the
//! contact rows bound the body's velocity relative to it: dᵀ(ẋ(u) − v_o) ≥ b.

use glam::DVec3;

use crate::centreline::Centreline;
use crate::error::GeometryError;
use crate::obstacle::Obstacle;
use crate::obstacle_spin::Spin;
use crate::tube_samples::TubeSamples;
use crate::wall::WallContact;

/// A path: (time s, offset cm) waypoints at strictly increasing times; none for a still
/// obstacle.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObstaclePath {
    waypoints: Vec<(f64, DVec3)>,
}

impl ObstaclePath {
    /// The path through `waypoints`: finite times, strictly increasing, finite offsets.
    pub fn new(waypoints: Vec<(f64, DVec3)>) -> Result<Self, GeometryError> {
        for (k, &(t, offset)) in waypoints.iter().enumerate() {
            let later = k == 0 || t > waypoints[k - 1].0;
            GeometryError::require_option(
                t.is_finite() && later,
                "path time",
                "finite and after the previous waypoint's",
                t,
            )?;
            GeometryError::require_option(
                offset.is_finite(),
                "path offset",
                "finite",
                offset.length(),
            )?;
        }
        Ok(Self { waypoints })
    }

    /// The offset at time `t` (cm): interpolated linearly, the end waypoints' beyond them,
    /// zero without waypoints.
    pub fn offset(&self, t: f64) -> DVec3 {
        match self.leg(t) {
            Leg::Still(offset) => offset,
            Leg::Moving { start: (t0, p0), end: (t1, p1) } => {
                p0 + (p1 - p0) * ((t - t0) / (t1 - t0))
            }
        }
    }

    /// The velocity at time `t` (cm/s): that of the leg starting at or before `t`, zero
    /// before the first waypoint and from the last on.
    pub fn velocity(&self, t: f64) -> DVec3 {
        match self.leg(t) {
            Leg::Still(_) => DVec3::ZERO,
            Leg::Moving { start: (t0, p0), end: (t1, p1) } => (p1 - p0) / (t1 - t0),
        }
    }

    fn leg(&self, t: f64) -> Leg {
        let Some(&(first_time, first)) = self.waypoints.first() else {
            return Leg::Still(DVec3::ZERO);
        };
        if t < first_time {
            return Leg::Still(first);
        }
        let next = self.waypoints.partition_point(|&(time, _)| time <= t);
        match self.waypoints.get(next) {
            Some(&end) => Leg::Moving { start: self.waypoints[next - 1], end },
            None => Leg::Still(self.waypoints[next - 1].1),
        }
    }
}

/// Where `t` falls on a path.
enum Leg {
    Still(DVec3),
    Moving { start: (f64, DVec3), end: (f64, DVec3) },
}

/// An obstacle, its path (a still one has an empty path) and its turn, if it turns.
#[derive(Debug, Clone, PartialEq)]
pub struct MovingObstacle {
    /// The obstacle as posed at offset zero.
    pub shape: Obstacle,
    /// Its path.
    pub path: ObstaclePath,
    /// Its turn: about an axis of its symmetry it moves the surface and not the shape.
    pub spin: Option<Spin>,
}

impl From<Obstacle> for MovingObstacle {
    fn from(shape: Obstacle) -> Self {
        MovingObstacle { shape, path: ObstaclePath::default(), spin: None }
    }
}

impl MovingObstacle {
    /// The obstacle where its path and turn have it at time `t`: the shape turned by the
    /// spin's R(t) about its reference point if the turn moves it ([`Spin::turns_shape`]),
    /// then moved by the path's offset.
    pub fn at(&self, t: f64) -> Obstacle {
        let turned = match self.spin {
            Some(spin) if spin.turns_shape() => {
                self.shape.rotated_about(spin.rotation(t), self.shape.reference_point())
            }
            _ => self.shape,
        };
        turned.translated(self.path.offset(t))
    }

    /// Appends to `out` the contacts of [`Obstacle::contacts`] with the obstacle where it is
    /// at time `t`, each carrying the velocity of the surface point nearest its sample x(u)
    /// then: the path's v, plus ω × (s − p) where it turns, s = x(u) − (gap + r(u)) n the
    /// surface point and p the obstacle's reference point.
    pub fn contacts(
        &self,
        (centreline, samples): (&Centreline, &TubeSamples),
        margin: f64,
        t: f64,
        out: &mut Vec<WallContact>,
    ) {
        let first = out.len();
        let obstacle = self.at(t);
        obstacle.contacts(centreline, samples, margin, out);
        let velocity = self.path.velocity(t);
        for contact in &mut out[first..] {
            contact.surface_velocity = match self.spin {
                None => velocity,
                Some(spin) => {
                    let surface = contact.point - (contact.gap + contact.radius) * contact.normal;
                    velocity + spin.surface_velocity(t, obstacle.reference_point(), surface)
                }
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_interpolates_its_waypoints_and_holds_its_ends() {
        let path = ObstaclePath::new(vec![
            (1.0, DVec3::ZERO),
            (3.0, DVec3::new(4.0, 0.0, 0.0)),
            (4.0, DVec3::new(4.0, 1.0, 0.0)),
        ])
        .expect("a path");
        assert_eq!(path.offset(0.0), DVec3::ZERO);
        assert_eq!(path.velocity(0.5), DVec3::ZERO);
        assert_eq!(path.offset(2.0), DVec3::new(2.0, 0.0, 0.0));
        assert_eq!(path.velocity(1.0), DVec3::new(2.0, 0.0, 0.0));
        assert_eq!(path.velocity(3.0), DVec3::new(0.0, 1.0, 0.0));
        assert_eq!(path.offset(10.0), DVec3::new(4.0, 1.0, 0.0));
        assert_eq!(path.velocity(4.0), DVec3::ZERO);
        assert_eq!(ObstaclePath::default().offset(5.0), DVec3::ZERO);
        assert!(ObstaclePath::new(vec![(1.0, DVec3::ZERO), (1.0, DVec3::X)]).is_err());
        assert!(ObstaclePath::new(vec![(f64::NAN, DVec3::ZERO)]).is_err());
    }
}
