//! Wall contact (`docs/physics.md` D10, "Constraint rows"): a body near the wall, seen as a sphere of radius
//! r_k at its centre c_k, gets the row `n_wᵀ ċ_k ≥ b(d)` with `d = n_w·(c_k − p_w) − r_k`.
//! Only the centre's velocity enters the normal row: the contact point is `c_k − r_k n_w` and
//! `n_w·(ω × (−r_k n_w)) = 0`. With friction the rows push along the pyramid's edges
//! (`friction.rs`) at the contact point, whose tangential velocity the body's spin does move.
//! A moving obstacle's rows bound the velocity relative to its surface.

use glam::DVec3;
use hagfish_geometry::WallContact;
use hagfish_solver::Rows;
use hagfish_tree::jacobian::add_point_row;
use hagfish_tree::{Data, Model};

use super::RowGroup;
use super::friction::{
    Friction, MAX_FRICTION_EDGES, contact_directions, contact_row, push_pyramid_bases,
    wall_contact_offset,
};

/// Appends the rows of each wall contact, id its index in `contacts`: one along the normal, or
/// with `friction` one along each edge of its friction pyramid (or the normal and two friction
/// rows of the exact cone); `radii` are the bodies' radii.
pub fn add_wall_rows(
    model: &Model,
    data: &Data,
    (contacts, radii): (&[WallContact], &[f64]),
    (time_step, push_out, friction): (f64, f64, Option<Friction>),
    rows: &mut Rows,
) {
    let mut directions = [DVec3::ZERO; MAX_FRICTION_EDGES];
    for (i, contact) in contacts.iter().enumerate() {
        let centre = data.body_centre(contact.body);
        let edges = contact_directions(contact.normal, DVec3::X, friction, &mut directions);
        let offset = wall_contact_offset(edges, radii[contact.body], contact.normal);
        // The centre itself, bit for bit, where there is no offset.
        let point = if edges == 1 { centre } else { centre + offset };
        let bases = push_pyramid_bases(rows, friction, edges, |axes, bases| {
            for (axis, base) in axes.into_iter().zip(bases) {
                add_point_row(model, data, contact.body, point, axis, 1.0, base);
            }
        });
        let first = rows.len();
        for (k, &direction) in directions[..edges].iter().enumerate() {
            let (source, stabilisation) = (RowGroup::Wall.source(i), (time_step, push_out));
            let gap = (contact.gap, direction.dot(contact.surface_velocity));
            let (kind, rhs) = contact_row(gap, stabilisation, friction, (k, first));
            match bases {
                Some(bases) => {
                    rows.push_combination(kind, source, rhs, (bases, direction.to_array()))
                }
                None => {
                    let row = rows.push_zeroed(kind, source, rhs);
                    add_point_row(model, data, contact.body, point, direction, 1.0, row);
                }
            }
        }
    }
}
