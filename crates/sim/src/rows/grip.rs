//! Grip rows (`docs/physics.md`, "Pulls at prescribed speed (grip)"; `hagfish_control::Grip`): six equality rows that
//! hold a body point on a moving target and the body at a held orientation,
//! `e_kᵀ P(x) q̇ = e_k·(v* + (β/h)(x* − x))` and `e_kᵀ Ω q̇ = e_k·(β/h) θ` for the world axes
//! e_k, with P(x) the point's Jacobian, Ω the body's angular-velocity Jacobian, θ the rotation
//! vector back to the held orientation and β the head rows' drift correction. The linear rows'
//! multipliers over h are the grip's force on the body (dyn), the angular rows' its moment
//! (dyn·cm).

use glam::DVec3;
use hagfish_control::Grip;
use hagfish_solver::{RowKind, Rows};
use hagfish_tree::jacobian::add_point_row;
use hagfish_tree::{Data, Model};

use super::RowGroup;
use super::breaks::{point_breaks, set_last_breaks};

/// The world axes of the grip's rows: ids 0–2 the linear rows, 3–5 the angular ones.
const AXES: [DVec3; 3] = [DVec3::X, DVec3::Y, DVec3::Z];

/// Appends the six rows of `grip`, ids 0…5 (see [`grip_row_push`]).
pub fn add_grip_rows(
    model: &Model,
    data: &Data,
    grip: &Grip,
    (time_step, correction): (f64, f64),
    rows: &mut Rows,
) {
    let rate = correction / time_step;
    let drift = grip.target - grip.point;
    for (k, axis) in AXES.into_iter().enumerate() {
        let rhs = axis.dot(grip.velocity + rate * drift);
        let row = rows.push_zeroed(RowKind::Equality, RowGroup::Grip.source(k), rhs);
        add_point_row(model, data, grip.body, grip.point, axis, 1.0, row);
        set_last_breaks(rows, point_breaks(model, [grip.body]));
    }
    for (k, axis) in AXES.into_iter().enumerate() {
        let rhs = axis.dot(rate * grip.rotation_error);
        let row = rows.push_zeroed(RowKind::Equality, RowGroup::Grip.source(3 + k), rhs);
        for joint in model.path_to_root(grip.body) {
            for a in joint.dofs() {
                row[a] += axis.dot(data.axes[a].angular);
            }
        }
        set_last_breaks(rows, point_breaks(model, [grip.body]));
    }
}

/// What a grip row's multiplier is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GripPush {
    /// A force along this world axis (ids 0–2).
    Force(DVec3),
    /// A moment about this world axis (ids 3–5).
    Moment(DVec3),
}

/// What grip row `id` pushes along.
pub fn grip_row_push(id: usize) -> GripPush {
    if id < 3 { GripPush::Force(AXES[id % 3]) } else { GripPush::Moment(AXES[id % 3]) }
}

/// The grip's force (dyn) and moment (dyn·cm) on its body in the last solve: the multipliers
/// of its rows over h.
pub fn grip_wrench(rows: &Rows, multipliers: &[f64], time_step: f64) -> (DVec3, DVec3) {
    let (mut force, mut moment) = (DVec3::ZERO, DVec3::ZERO);
    for (source, &lambda) in rows.sources().iter().zip(multipliers) {
        if RowGroup::of(source.tag) != Some(RowGroup::Grip) {
            continue;
        }
        match grip_row_push(source.id) {
            GripPush::Force(axis) => force += axis * (lambda / time_step),
            GripPush::Moment(axis) => moment += axis * (lambda / time_step),
        }
    }
    (force, moment)
}
