//! Head fixation (`docs/physics.md` D9): bilateral rows `e_kᵀ q̇ = −(β/h)(q_k − q_k*)` on every
//! DOF of each root joint (anchored to the world), holding the head at its target pose with
//! Baumgarte correction of drift.

use hagfish_solver::{RowKind, Rows};

use super::RowGroup;
use super::breaks::{joint_breaks, set_last_breaks};
use hagfish_tree::{Model, State};

/// Appends one equality row per root-joint DOF, targets `q* = q_rest`.
pub fn add_head_rows(
    model: &Model,
    state: &State,
    time_step: f64,
    correction: f64,
    rows: &mut Rows,
) {
    for joint in model.joints().iter().filter(|j| j.parent.is_none()) {
        for k in joint.dofs() {
            let error = state.q[k] - model.dofs()[k].rest;
            let row = rows.push_zeroed(
                RowKind::Equality,
                RowGroup::Head.source(k),
                -correction * error / time_step,
            );
            row[k] = 1.0;
            set_last_breaks(rows, joint_breaks(model, k));
        }
    }
}
