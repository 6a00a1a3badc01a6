//! Wall contact (`docs/physics.md` D10, "Constraint rows"): a body near the wall, seen as a sphere of radius
//! r_k at its centre c_k, gets the row `n_wᵀ ċ_k ≥ b(d)` with `d = n_w·(c_k − p_w) − r_k`.
//! Only the centre's velocity enters: the contact point is `c_k − r_k n_w` and
//! `n_w·(ω × (−r_k n_w)) = 0`.

use hagfish_geometry::WallContact;
use hagfish_solver::Rows;
use hagfish_tree::jacobian::add_point_row;
use hagfish_tree::{Data, Model};

use super::RowGroup;
use super::stabilisation::push_unilateral_row;

/// Appends one row per wall contact, id its index in `contacts`.
pub fn add_wall_rows(
    model: &Model,
    data: &Data,
    contacts: &[WallContact],
    time_step: f64,
    push_out: f64,
    rows: &mut Rows,
) {
    for (i, contact) in contacts.iter().enumerate() {
        let row = push_unilateral_row(rows, RowGroup::Wall, i, contact.gap, time_step, push_out);
        let centre = data.body_centre(contact.body);
        add_point_row(model, data, contact.body, centre, contact.normal, 1.0, row);
    }
}
