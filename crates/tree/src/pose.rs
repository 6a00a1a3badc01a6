//! Laying a chain along a curve: the joint angles that put every bending joint on a polyline
//! (a body's initial shape, a follow-the-leader tie's target).
//!
//! Bodies meet a bending (universal) joint every second joint, so the chain is a polyline of
//! straight runs between bending joints whose corners are placed on the curve, walking from
//! the head: each run's far corner is the first point of the curve at the run's length (a
//! chord) from its near one. Each bending joint turns by yaw (about its y axis) then pitch
//! (about z) onto its run's direction, in the frame the joints before it have turned; the
//! twist joints stay at 0.

use glam::{DMat3, DVec3};

use crate::joint::JointKind;
use crate::model::Model;

/// Writes into `q` (one entry per DOF of `model`) the joint angles that lay `model` — a chain
/// from the head at the origin along +X, with twist and bending joints — along the polyline
/// `points` (cm, starting at the origin). Twist DOFs and the DOFs of a chain longer than the
/// curve's end are set to 0 (the chain goes on straight); a curve of fewer than 2 points leaves
/// the chain straight.
/// O(bodies + points), no allocation.
pub fn pose_along(model: &Model, points: &[DVec3], q: &mut [f64]) {
    q.fill(0.0);
    if points.len() < 2 {
        return;
    }
    let mut walker = CurveWalker { points, segment: 0, at: DVec3::ZERO };
    let mut frame = DMat3::IDENTITY;
    let (bodies, joints) = (model.bodies(), model.joints());
    let mut index = 0;
    while index < bodies.len() {
        // The bodies up to the next bending joint turn with this one: one straight run.
        let mut run = bodies[index].length;
        let mut next = index + 1;
        while next < bodies.len() && !matches!(joints[next].kind, JointKind::UniversalYz) {
            run += bodies[next].length;
            next += 1;
        }
        let (corner, next_corner) = walker.advance(run);
        if next_corner == corner {
            return;
        }
        if matches!(joints[index].kind, JointKind::UniversalYz) {
            let local = frame.transpose() * (next_corner - corner).normalize();
            let (yaw, pitch) = ((-local.z).atan2(local.x), local.y.clamp(-1.0, 1.0).asin());
            let dofs = joints[index].dofs();
            q[dofs.start] = yaw;
            q[dofs.start + 1] = pitch;
            frame = frame * DMat3::from_rotation_y(yaw) * DMat3::from_rotation_z(pitch);
        }
        index = next;
    }
}

/// Walks along a polyline by chords: each step goes to the first point ahead at a given
/// distance from the last point reached.
struct CurveWalker<'a> {
    points: &'a [DVec3],
    /// The polyline segment the last point reached lies on.
    segment: usize,
    /// The last point reached.
    at: DVec3,
}

impl CurveWalker<'_> {
    /// Steps on by `chord`: returns the point it started from and the point reached (or the
    /// polyline's end, if it is nearer than `chord`).
    fn advance(&mut self, chord: f64) -> (DVec3, DVec3) {
        let from = self.at;
        let mut a = from;
        while self.segment + 1 < self.points.len() {
            let b = self.points[self.segment + 1];
            if from.distance(b) >= chord {
                self.at = crossing(from, chord, a, b);
                return (from, self.at);
            }
            self.segment += 1;
            a = b;
        }
        self.at = a;
        (from, a)
    }
}

/// The point of segment `a`–`b` at distance `chord` from `from`, given that `a` is closer
/// than `chord` and `b` is not (bisection).
fn crossing(from: DVec3, chord: f64, a: DVec3, b: DVec3) -> DVec3 {
    let (mut low, mut high) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (low + high);
        if from.distance(a.lerp(b, mid)) < chord {
            low = mid;
        } else {
            high = mid;
        }
    }
    a.lerp(b, 0.5 * (low + high))
}
