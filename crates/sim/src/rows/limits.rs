//! Joint limits (`docs/physics.md`, "Constraint rows"): per DOF with finite limits, the lower row
//! `e_kᵀ q̇ ≥ b(q_k − lo)` and the upper row `−e_kᵀ q̇ ≥ b(hi − q_k)`, added when the gap is
//! below `max(margin, 2h|q̇_k|)`. A joint far from its limit can still be thrown past it within
//! one step by an impact elsewhere; [`add_overshooting_limit_rows`] adds the rows of DOFs whose
//! solved velocity would cross a limit, for the pipeline to solve again. (REDMAX's MATLAB upper row has the opposite sign, which allows
//! further violation; the test `upper_limit_row_stops_the_joint` pins ours.)

use hagfish_solver::Rows;
use hagfish_tree::{Model, State};

use super::RowGroup;
use super::breaks::{joint_breaks, set_last_breaks};
use super::stabilisation::push_unilateral_row;

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
        for (gap, sign) in [(state.q[k] - dof.lower, 1.0), (dof.upper - state.q[k], -1.0)] {
            if has_row(gap, state.qdot[k], time_step, dof_margin(dof, margin)) {
                push_unilateral_row(rows, RowGroup::Limit, k, gap, time_step, push_out)[k] = sign;
                set_last_breaks(rows, joint_breaks(model, k));
            }
        }
    }
}

/// Whether [`add_limit_rows`] gives a limit at `gap` (rad) a row: closer than `margin`, or
/// than twice the distance the DOF's rate covers in a step.
fn has_row(gap: f64, rate: f64, time_step: f64, margin: f64) -> bool {
    gap < margin.max(2.0 * time_step * rate.abs())
}

/// The margin of `dof`: `margin`, but at most a quarter of the DOF's range.
fn dof_margin(dof: &hagfish_tree::DofParams, margin: f64) -> f64 {
    margin.min(0.25 * (dof.upper - dof.lower))
}

/// Appends limit rows for the DOFs that the solved velocities `qdot_next` would carry past a
/// limit in this step (`q_k + h q̇_k` outside `[lo, hi]`) and that [`add_limit_rows`] (same
/// `margin`) gave no row; returns how many were added. A limit that has a row keeps the one
/// it has: a penetrated one may still be past its limit after the step (its row asks only
/// for `push_out` of the way back), and another row would duplicate it.
pub fn add_overshooting_limit_rows(
    model: &Model,
    state: &State,
    qdot_next: &[f64],
    time_step: f64,
    margin: f64,
    push_out: f64,
    rows: &mut Rows,
) -> usize {
    let mut added = 0;
    for (k, gap, sign) in overshooting_limits(model, state, qdot_next, time_step, margin) {
        push_unilateral_row(rows, RowGroup::Limit, k, gap, time_step, push_out)[k] = sign;
        set_last_breaks(rows, joint_breaks(model, k));
        added += 1;
    }
    added
}

/// True when [`add_overshooting_limit_rows`] would add a row (same arguments).
pub fn overshoots_limit(
    model: &Model,
    state: &State,
    qdot_next: &[f64],
    time_step: f64,
    margin: f64,
) -> bool {
    overshooting_limits(model, state, qdot_next, time_step, margin).next().is_some()
}

/// (DOF, gap, sign) of every limit that `qdot_next` carries past within the step and that
/// [`add_limit_rows`] gave no row, lower limit before upper.
fn overshooting_limits<'a>(
    model: &'a Model,
    state: &'a State,
    qdot_next: &'a [f64],
    time_step: f64,
    margin: f64,
) -> impl Iterator<Item = (usize, f64, f64)> + 'a {
    // The DOFs whose next position leaves [lo, hi] first (next − lo < 0 ⇔ next < lo for
    // floating-point numbers), so that the rest of a long chain costs a comparison each.
    let next = move |(k, dof): (usize, &'a hagfish_tree::DofParams)| {
        (k, dof, state.q[k] + time_step * qdot_next[k])
    };
    let crossing = |&(_, dof, next): &(usize, &hagfish_tree::DofParams, f64)| {
        next < dof.lower || dof.upper < next
    };
    model.dofs().iter().enumerate().map(next).filter(crossing).flat_map(move |(k, dof, next)| {
        [
            (state.q[k] - dof.lower, next - dof.lower, 1.0),
            (dof.upper - state.q[k], dof.upper - next, -1.0),
        ]
        .into_iter()
        .filter(move |&(gap, next_gap, _)| {
            next_gap < 0.0 && !has_row(gap, state.qdot[k], time_step, dof_margin(dof, margin))
        })
        .map(move |(gap, _, sign)| (k, gap, sign))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use hagfish_tree::{BodySpec, DofParams, JointKind, ModelBuilder, Transform};

    /// One body on a revolute joint limited to ±0.1 rad.
    fn hinge() -> Model {
        let mut builder = ModelBuilder::new();
        builder.add_body(BodySpec {
            parent: None,
            joint: JointKind::Revolute { axis: DVec3::Z },
            joint_offset: Transform::IDENTITY,
            body_offset: Transform::from_translation(DVec3::X),
            mass: 1.0,
            principal_inertia: DVec3::splat(0.1),
            radius: 0.1,
            length: 2.0,
            skin: None,
            dofs: vec![DofParams { lower: -0.1, upper: 0.1, ..DofParams::default() }],
        });
        builder.build().expect("a valid hinge")
    }

    #[test]
    fn a_penetrated_limit_keeps_one_row_however_often_the_step_is_solved_again() {
        let (model, h, margin, push_out) = (hinge(), 0.01, 0.01, 0.5);
        let mut state = State::rest(&model);
        state.q[0] = 0.12; // 0.02 rad past the upper limit
        let mut rows = Rows::new(1);
        add_limit_rows(&model, &state, h, margin, push_out, &mut rows);
        assert_eq!(rows.len(), 1);
        // The row −q̇ ≥ 0.5 · 0.02 / h met exactly leaves the joint 0.01 rad past its limit.
        let solved = [-rows.rhs()[0]];
        assert!(state.q[0] + h * solved[0] > 0.1);
        for _ in 0..3 {
            let added = add_overshooting_limit_rows(
                &model, &state, &solved, h, margin, push_out, &mut rows,
            );
            assert_eq!(added, 0, "the penetrated limit already has its row");
        }
        assert_eq!(rows.len(), 1);
    }

    #[test]
    fn the_margin_never_covers_a_quarter_of_the_range() {
        // ±0.1 rad: with a 0.1 rad margin a joint at rest would get both rows; the margin is
        // held to 0.05 rad, a quarter of the range.
        let (model, h, margin) = (hinge(), 0.01, 0.1);
        let mut state = State::rest(&model);
        let mut rows = Rows::new(1);
        add_limit_rows(&model, &state, h, margin, 0.5, &mut rows);
        assert_eq!(rows.len(), 0, "at rest, 0.1 rad from either limit");
        state.q[0] = 0.06;
        add_limit_rows(&model, &state, h, margin, 0.5, &mut rows);
        assert_eq!(rows.len(), 1, "0.04 rad from the upper limit");
    }

    #[test]
    fn a_joint_thrown_past_a_limit_it_had_no_row_for_gets_one() {
        let (model, h, margin, push_out) = (hinge(), 0.01, 0.01, 0.5);
        let state = State::rest(&model);
        let mut rows = Rows::new(1);
        add_limit_rows(&model, &state, h, margin, push_out, &mut rows);
        assert!(rows.is_empty(), "far from both limits at rest");
        let thrown = [20.0]; // 0.2 rad in one step
        assert_eq!(
            add_overshooting_limit_rows(&model, &state, &thrown, h, margin, push_out, &mut rows),
            1
        );
        assert_eq!(rows.row(0).map(|r| r.to_vec()), Some(vec![-1.0]), "the upper row");
    }
}
