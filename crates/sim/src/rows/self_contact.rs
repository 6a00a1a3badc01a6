//! Self contact on the centreline (`docs/physics.md`, "Constraint rows"): a spline point is a fixed blend of
//! body centres, `x(u) = Σ_m w_m(u) c_m`, so its velocity is `P(u) q̇` with
//! `P(u) = Σ_m w_m R_m [0 I₃] J_m`. With the normal n from the anterior point a to the
//! posterior point b, the row is `nᵀ(P(u_b) − P(u_a)) q̇ ≥ b(d)`: the gap may not close
//! faster than allowed.

use glam::DVec3;
use hagfish_geometry::{SelfContact, SplineWeights};
use hagfish_solver::Rows;
use hagfish_tree::jacobian::add_point_rows;
use hagfish_tree::{Data, Model};

use super::RowGroup;
use super::stabilisation::push_unilateral_row;

/// Appends one row per self contact, id its index in `contacts` (both spline points blended in one walk to the root).
pub fn add_self_contact_rows(
    model: &Model,
    data: &Data,
    contacts: &[SelfContact],
    time_step: f64,
    push_out: f64,
    rows: &mut Rows,
) {
    for (i, contact) in contacts.iter().enumerate() {
        let row = push_unilateral_row(rows, RowGroup::Contact, i, contact.gap, time_step, push_out);
        let mut points = [(0, DVec3::ZERO, 0.0); 2 * SplineWeights::CAPACITY];
        let mut count = 0;
        for (weights, sign) in [(&contact.weights_b, 1.0), (&contact.weights_a, -1.0)] {
            for (body, w) in weights.iter() {
                points[count] = (body, data.body_centre(body), sign * w);
                count += 1;
            }
        }
        add_point_rows(model, data, &points[..count], contact.normal, row);
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
    let mut points = [(0, DVec3::ZERO, 0.0); SplineWeights::CAPACITY];
    let mut count = 0;
    for (body, w) in weights.iter() {
        points[count] = (body, data.body_centre(body), scale * w);
        count += 1;
    }
    add_point_rows(model, data, &points[..count], direction, row);
}
