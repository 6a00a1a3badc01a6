//! Self contact on the centreline (`docs/physics.md` §5): a spline point is a fixed blend of
//! body centres, `x(u) = Σ_m w_m(u) c_m`, so its velocity is `P(u) q̇` with
//! `P(u) = Σ_m w_m R_m [0 I₃] J_m`. With the normal n from the anterior point a to the
//! posterior point b, the row is `nᵀ(P(u_b) − P(u_a)) q̇ ≥ b(d)`: the gap may not close
//! faster than allowed.

use glam::DVec3;
use hagfish_geometry::{SelfContact, SplineWeights};
use hagfish_solver::{RowGroup, RowKind, Rows};
use hagfish_tree::jacobian::add_point_row;
use hagfish_tree::{Data, Model};

use super::stabilisation::unilateral_rhs;

/// Appends one row per self contact.
pub fn add_self_contact_rows(
    model: &Model,
    data: &Data,
    contacts: &[SelfContact],
    time_step: f64,
    push_out: f64,
    rows: &mut Rows,
) {
    for contact in contacts {
        let rhs = unilateral_rhs(contact.gap, time_step, push_out);
        let row = rows.push_zeroed(RowKind::Inequality, RowGroup::Contact, rhs);
        add_spline_point_row(model, data, &contact.weights_b, contact.normal, 1.0, row);
        add_spline_point_row(model, data, &contact.weights_a, contact.normal, -1.0, row);
    }
}

/// Adds `scale · dᵀ P(u)` to `row`, with P(u) the velocity Jacobian of the spline point whose
/// body weights are `weights`, and `d` a world direction.
pub fn add_spline_point_row(
    model: &Model,
    data: &Data,
    weights: &SplineWeights,
    direction: DVec3,
    scale: f64,
    row: &mut [f64],
) {
    for (body, w) in weights.iter() {
        add_point_row(model, data, body, data.body_centre(body), direction, scale * w, row);
    }
}
