//! Right-hand sides of unilateral rows from a gap (`docs/physics.md`, "Constraint rows").

use hagfish_solver::{RowKind, Rows};

use super::RowGroup;

/// The velocity bound of a unilateral row `ḋ ≥ b` for a gap `d` (d ≥ 0 feasible):
/// speculative `b = −d/h` when `d ≥ 0` (the gap may close exactly within this step, so the
/// contact never pops), push-out `b = −(β/h)·d` when `d < 0` (a fraction β of the
/// penetration is removed per step).
pub fn unilateral_rhs(gap: f64, time_step: f64, push_out: f64) -> f64 {
    if gap >= 0.0 { -gap / time_step } else { -push_out * gap / time_step }
}

/// Appends the unilateral row of object `id` in `group` for a gap `d` (right-hand side
/// [`unilateral_rhs`]) and returns its coefficients, zeroed, to be filled in.
pub(super) fn push_unilateral_row(
    rows: &mut Rows,
    group: RowGroup,
    id: usize,
    gap: f64,
    time_step: f64,
    push_out: f64,
) -> &mut [f64] {
    let rhs = unilateral_rhs(gap, time_step, push_out);
    rows.push_zeroed(RowKind::Inequality, group.source(id), rhs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speculative_when_open_push_out_when_penetrating() {
        assert_eq!(unilateral_rhs(0.02, 0.01, 0.2), -2.0);
        assert!((unilateral_rhs(-0.01, 0.01, 0.2) - 0.2).abs() < 1e-15);
        assert_eq!(unilateral_rhs(0.0, 0.01, 0.2), 0.0);
    }
}
