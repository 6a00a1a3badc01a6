//! Thigmotaxis rows (thesis Eq. 5.1; `hagfish_control::ThigmoParameters`): for a requested
//! strand of a self contact, with a the anterior and b the posterior point,
//! `t_aᵀ(P(u_a) − P(u_b)) q̇ ≥ v_a` or `t_bᵀ(P(u_b) − P(u_a)) q̇ ≥ v_b`. No stabilisation term.
//! Soft: the slack penalty is the row's largest impulse, `max_force · h`.
//!
//! A row is confined to its request's force space ([`Confinement::confine`], the scenario's
//! [`ForceSpace`] as the step carries it): with
//! `BendingOnly` its twist entries are zero, so its force `cλ` has no twist torque and the row
//! asks the sliding speed of the bending velocities alone; with `Modes` it is `B(Bᵀc)`, in the
//! span of the basis B.
//!
//! A negative target asks for sliding the other way (the knot moves tail-ward): the row becomes
//! `−tᵀ(P(u_this) − P(u_other)) q̇ ≥ |v|`. Merely lowering the bound of the head-ward row below
//! zero would only *allow* tail-ward sliding, never drive it.

use glam::DVec3;
#[cfg(doc)]
use hagfish_control::ForceSpace;
use hagfish_control::{Confinement, Strand, ThigmoRequest};
use hagfish_geometry::{SelfContact, SplineWeights};
use hagfish_solver::{RowKind, Rows};
use hagfish_tree::{Data, Model};

use super::RowGroup;
use super::breaks::{point_breaks, set_last_breaks};
use super::self_contact::add_spline_point_row;

/// Appends one soft row per request, id its index in `requests` (requests naming a missing
/// contact are skipped), each confined to its request's force space; `twist_dofs` are the
/// indices of the twist DOFs ([`twist_dofs`]), `scratch` (one value per DOF) holds a modal
/// space's `Bᵀc`.
#[allow(clippy::too_many_arguments)] // the stage's inputs, each read once
pub fn add_thigmo_rows(
    model: &Model,
    data: &Data,
    contacts: &[SelfContact],
    requests: &[ThigmoRequest],
    twist_dofs: &[usize],
    scratch: &mut [f64],
    time_step: f64,
    rows: &mut Rows,
) {
    for (i, request) in requests.iter().enumerate() {
        let Some(contact) = contacts.get(request.contact) else { continue };
        let weight = request.max_force * time_step;
        let row = rows.push_zeroed(
            RowKind::SoftInequality { weight },
            RowGroup::Thigmo.source(i),
            request.speed.abs(),
        );
        let (this, other, tangent) = thigmo_strands(request, contact);
        add_spline_point_row(model, data, this, tangent, 1.0, row);
        add_spline_point_row(model, data, other, tangent, -1.0, row);
        request.confinement.confine(twist_dofs, scratch, row);
        if request.confinement == Confinement::Full {
            let bodies = this.iter().chain(other.iter()).map(|(body, _)| body);
            set_last_breaks(rows, point_breaks(model, bodies));
        }
    }
}

/// The indices of the twist DOFs of `model`: those about the body's long axis (X), as
/// [`crate::dof_labels`] labels them.
pub fn twist_dofs(model: &Model) -> Vec<usize> {
    let labels = crate::dof_labels(model);
    labels.iter().enumerate().filter(|(_, l)| l.axis == 'X').map(|(k, _)| k).collect()
}

/// The strand a request drives, the other strand and the direction of the row
/// (`tᵀ(P_this − P_other) q̇ ≥ |v|`): the driven strand's tail-ward tangent, reversed for a
/// negative target speed.
pub(crate) fn thigmo_strands<'c>(
    request: &ThigmoRequest,
    contact: &'c SelfContact,
) -> (&'c SplineWeights, &'c SplineWeights, DVec3) {
    let (this, other, tail_ward) = match request.strand {
        Strand::Anterior => (&contact.weights_a, &contact.weights_b, contact.tangent_a),
        Strand::Posterior => (&contact.weights_b, &contact.weights_a, contact.tangent_b),
    };
    (this, other, if request.speed < 0.0 { -tail_ward } else { tail_ward })
}
