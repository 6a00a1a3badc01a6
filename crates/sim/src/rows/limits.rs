//! Joint limits (`docs/physics.md`, "Constraint rows"): per DOF with finite limits, the lower row
//! `e_kᵀ q̇ ≥ b(q_k − lo)` and the upper row `−e_kᵀ q̇ ≥ b(hi − q_k)`, added when the gap is
//! below `max(margin, 2h|q̇_k|)`. A joint far from its limit can still be thrown past it within
//! one step by an impact elsewhere; [`add_overshooting_limit_rows`] adds the rows of DOFs whose
//! solved velocity would cross a limit, for the pipeline to solve again. (REDMAX's MATLAB upper row has the opposite sign, which allows
//! further violation; the test `upper_limit_row_stops_the_joint` pins ours.)

use hagfish_solver::{RowGroup, RowKind, Rows};
use hagfish_tree::{Model, State};

use super::stabilisation::unilateral_rhs;

/// Appends the active lower and upper limit rows.
pub fn add_limit_rows(
    model: &Model,
    state: &State,
    time_step: f64,
    margin: f64,
    push_out: f64,
    rows: &mut Rows,
) {
    for (k, dof) in model.dofs().iter().enumerate() {
        let active_within = margin.max(2.0 * time_step * state.qdot[k].abs());
        for (gap, sign) in [(state.q[k] - dof.lower, 1.0), (dof.upper - state.q[k], -1.0)] {
            if gap < active_within {
                let rhs = unilateral_rhs(gap, time_step, push_out);
                rows.push_zeroed(RowKind::Inequality, RowGroup::Limit, rhs)[k] = sign;
            }
        }
    }
}

/// Appends limit rows for the DOFs that the solved velocities `qdot_next` would carry past a
/// limit in this step (`q_k + h q̇_k` outside `[lo, hi]`); returns how many were added. A DOF
/// that already has a row for that limit cannot overshoot it, so no row is added twice.
pub fn add_overshooting_limit_rows(
    model: &Model,
    state: &State,
    qdot_next: &[f64],
    time_step: f64,
    push_out: f64,
    rows: &mut Rows,
) -> usize {
    let mut added = 0;
    for (k, dof) in model.dofs().iter().enumerate() {
        let next = state.q[k] + time_step * qdot_next[k];
        for (gap, next_gap, sign) in [
            (state.q[k] - dof.lower, next - dof.lower, 1.0),
            (dof.upper - state.q[k], dof.upper - next, -1.0),
        ] {
            if next_gap < 0.0 {
                let rhs = unilateral_rhs(gap, time_step, push_out);
                rows.push_zeroed(RowKind::Inequality, RowGroup::Limit, rhs)[k] = sign;
                added += 1;
            }
        }
    }
    added
}
