//! Self contact on the centreline (`docs/physics.md`, "Constraint rows"): a spline point is a fixed blend of
//! body centres, `x(u) = Σ_m w_m(u) c_m`, so its velocity is `P(u) q̇` with
//! `P(u) = Σ_m w_m R_m [0 I₃] J_m`. With the normal n from the anterior point a to the
//! posterior point b, the row is `nᵀ(P(u_b) − P(u_a)) q̇ ≥ b(d)`: the gap may not close
//! faster than allowed. Where the body has a skin, d is the gap between the cores and a second
//! row on the same `nᵀ(P(u_b) − P(u_a))`, the skin's spring, is compliant (`crate::skin`).

use glam::DVec3;
use hagfish_geometry::{Centreline, SelfContact, SplineWeights};
use hagfish_solver::{RowKind, Rows};
use hagfish_tree::jacobian::{add_point_rows, add_point_rows_along};
use hagfish_tree::{Data, Model};

use super::RowGroup;
use super::breaks::{point_breaks, set_last_breaks};
use super::friction::{
    Friction, MAX_FRICTION_EDGES, contact_directions, contact_row, push_pyramid_bases,
};
use crate::skin::SkinLayer;

/// Appends the rows of each self contact, id its index in `contacts` (both spline points
/// blended in one walk to the root): on the core gap, one along the normal, or with
/// `friction` one along each edge of its friction pyramid (or the exact cone's normal and
/// friction rows; `friction.rs`); and where `skin` has a skin at the contact (on
/// `centreline`) and the contact carries a spring (`skin_carriers`, one flag per contact;
/// `None`: all do, [`crate::skin::SkinRecords`]) the skin's compliant row `ḋ + ελ ≥ −g/h`
/// after it, tagged [`RowGroup::Skin`].
#[allow(clippy::too_many_arguments)] // the stage's inputs, each read once
pub fn add_self_contact_rows(
    model: &Model,
    data: &Data,
    contacts: &[SelfContact],
    centreline: &Centreline,
    (skin, skin_carriers): (&SkinLayer, Option<&[bool]>),
    (time_step, push_out, friction): (f64, f64, Option<Friction>),
    rows: &mut Rows,
) {
    let mut directions = [DVec3::ZERO; MAX_FRICTION_EDGES];
    for (i, contact) in contacts.iter().enumerate() {
        let mut points = [(0, DVec3::ZERO, 0.0); 2 * SplineWeights::CAPACITY];
        let mut count = 0;
        for (weights, sign) in [(&contact.weights_b, 1.0), (&contact.weights_a, -1.0)] {
            for (body, w) in weights.iter() {
                points[count] = (body, data.body_centre(body), sign * w);
                count += 1;
            }
        }
        let contact_skin = skin.at(contact, centreline);
        let core_gap = contact_skin.map_or(contact.gap, |s| s.core_gap);
        let edges =
            contact_directions(contact.normal, contact.tangent_a, friction, &mut directions);
        let contact_points = &points[..count];
        let breaks = point_breaks(model, contact_points.iter().map(|p| p.0));
        let bases = push_pyramid_bases(rows, friction, edges, |axes, bases| {
            add_point_rows_along(model, data, contact_points, axes, bases);
        });
        if let (Some(first), Some(breaks)) = (bases, breaks) {
            rows.set_base_breaks(first, breaks);
        }
        let first = rows.len();
        for (k, &direction) in directions[..edges].iter().enumerate() {
            let (source, stabilisation) = (RowGroup::Contact.source(i), (time_step, push_out));
            let gap = (core_gap, 0.0);
            let (kind, rhs) = contact_row(gap, stabilisation, friction, (k, first));
            match bases {
                Some(bases) => {
                    rows.push_combination(kind, source, rhs, (bases, direction.to_array()))
                }
                None => {
                    let row = rows.push_zeroed(kind, source, rhs);
                    add_point_rows(model, data, contact_points, direction, row);
                    set_last_breaks(rows, breaks);
                }
            }
        }
        let carries_spring = skin_carriers.is_none_or(|carriers| carriers[i]);
        if let Some(contact_skin) = contact_skin.filter(|_| carries_spring) {
            let kind = RowKind::Compliant { compliance: contact_skin.compliance(time_step) };
            let spring = rows.push_zeroed(kind, RowGroup::Skin.source(i), -contact.gap / time_step);
            add_point_rows(model, data, &points[..count], contact.normal, spring);
            set_last_breaks(rows, breaks);
        }
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
