//! Wall and obstacle contact (`docs/physics.md` D10, "Constraint rows", "Obstacles"): a body
//! near the wall, seen as a sphere of radius r_k at its centre c_k, gets the row
//! `n_wᵀ ċ_k ≥ b(d)` with `d = n_w·(c_k − p_w) − r_k`; a tube sample x(u) = Σ w_m c_m between
//! centres near an obstacle the row `nᵀ ẋ(u) ≥ b(d)`, `ẋ(u) = Σ w_m ċ_m`.
//! Only the centre's velocity enters the normal row: the contact point is `c_k − r_k n_w` and
//! `n_w·(ω × (−r_k n_w)) = 0`. With friction the rows push along the pyramid's edges
//! (`friction.rs`) at the contact point, whose tangential velocity the body's spin does move.
//! A moving obstacle's rows bound the velocity relative to its surface.

use glam::DVec3;
use hagfish_geometry::{SplineWeights, WallContact};
use hagfish_solver::Rows;
use hagfish_tree::jacobian::{add_point_row, add_point_rows};
use hagfish_tree::{Data, Model};

use super::RowGroup;
use super::breaks::{point_breaks, set_last_breaks};
use super::friction::{
    Friction, MAX_FRICTION_EDGES, contact_directions, contact_row, push_pyramid_bases,
    wall_contact_offset,
};

/// Appends the rows of each wall or obstacle contact, id its index in `contacts`: one along the
/// normal, or with `friction` one along each edge of its friction pyramid (or the normal and
/// two friction rows of the exact cone). A body's sphere acts at its centre (or its contact
/// point c − r n̂ with friction); a sample between centres at the blend Σ w_m (c_m + o) of the
/// same offsets o from its bodies' centres, whose velocity is the tube point's ẋ(u) (plus the
/// blended spin's at the surface).
pub fn add_wall_rows(
    model: &Model,
    data: &Data,
    contacts: &[WallContact],
    (time_step, push_out, friction): (f64, f64, Option<Friction>),
    rows: &mut Rows,
) {
    let mut directions = [DVec3::ZERO; MAX_FRICTION_EDGES];
    for (i, contact) in contacts.iter().enumerate() {
        let edges = contact_directions(contact.normal, DVec3::X, friction, &mut directions);
        let offset = wall_contact_offset(edges, contact.radius, contact.normal);
        let mut points = [(0, DVec3::ZERO, 0.0); SplineWeights::CAPACITY];
        let mut count = 0;
        for (body, w) in contact.weights.iter() {
            // The centre itself, bit for bit, where there is no offset.
            let centre = data.body_centre(body);
            points[count] = (body, if edges == 1 { centre } else { centre + offset }, w);
            count += 1;
        }
        let points = &points[..count];
        // A body's sphere: its one point's rows walk by themselves, as they always have.
        let add_rows = |axis: DVec3, row: &mut [f64]| match contact.body() {
            Some(body) => add_point_row(model, data, body, points[0].1, axis, 1.0, row),
            None => add_point_rows(model, data, points, axis, row),
        };
        let breaks = point_breaks(model, points.iter().map(|p| p.0));
        let bases = push_pyramid_bases(rows, friction, edges, |axes, bases| {
            for (axis, base) in axes.into_iter().zip(bases) {
                add_rows(axis, base);
            }
        });
        if let (Some(first), Some(breaks)) = (bases, breaks) {
            rows.set_base_breaks(first, breaks);
        }
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
                    add_rows(direction, rows.push_zeroed(kind, source, rhs));
                    set_last_breaks(rows, breaks);
                }
            }
        }
    }
}
