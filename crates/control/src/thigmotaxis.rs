//! Thigmotaxic inverse dynamics (thesis §5.2, Eq. 5.1; D11, D14 of docs/physics.md).
//!
//! On the first and the last self contact (sorted by the anterior parameter u_a; a is the
//! anterior point, b the posterior one, tangents t pointing tail-ward), the controller asks for
//! two velocity inequalities
//!
//! `t_aᵀ(P(u_a) − P(u_b)) q̇ ≥ v_a`  and  `t_bᵀ(P(u_b) − P(u_a)) q̇ ≥ v_b`:
//!
//! each strand slides tail-ward relative to the other by at least v, which moves the knot
//! head-ward (negative v moves it tail-ward). The rows are soft (a penalised slack, capped at
//! `max_force_dyn` per row) so a jammed knot cannot make the step infeasible. Their
//! multipliers, divided by h, are the control forces: the thigmotaxic force field. A small
//! force on the last body along its tangent keeps the tail straight so that no contact outside
//! the knot becomes "last".

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, PointForce};
use crate::force_space::{Confinement, ForceSpace};
use crate::replay::Replay;

/// Target sliding speeds (cm/s) at one contact: anterior strand a, posterior strand b.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SlidingTargets {
    /// v_a (cm/s): strand a slides tail-ward relative to b at least this fast.
    pub v_a: f64,
    /// v_b (cm/s): strand b slides tail-ward relative to a at least this fast.
    pub v_b: f64,
}

/// Parameters of a thigmotaxis phase (thesis Tables 5.1, 6.1).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThigmoParameters {
    /// Targets at the first (head-most) contact.
    pub head: SlidingTargets,
    /// Targets at the last (tail-most) contact.
    pub tail: SlidingTargets,
    /// Force on the last body along its tangent, tail-ward (dyn).
    pub tail_pull_dyn: f64,
    /// Largest force a thigmotaxis row may exert (dyn): its slack penalty.
    pub max_force_dyn: f64,
    /// The generalized forces the rows may exert (default: every DOF).
    #[serde(default)]
    pub force_space: ForceSpace,
    /// A recorded field to apply open loop instead of the rows (default: none, the rows).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replay: Option<Replay>,
}

impl ThigmoParameters {
    /// The tail pull: `tail_pull_dyn` on the last body along its tangent.
    fn actuate_pull(&self, context: &ControlContext<'_>, out: &mut Actuation) {
        let tail = context.model.body_count() - 1;
        let tangent = context.centreline.unit_tangent(tail as f64);
        out.forces.push(PointForce {
            body: tail,
            point: context.centre(tail),
            force: tangent.normalize_or(DVec3::X) * self.tail_pull_dyn,
        });
    }
}

/// Which end of a contact a thigmotaxis row drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strand {
    /// The anterior point a: row `t_aᵀ(P(u_a) − P(u_b)) q̇ ≥ v_a`.
    Anterior,
    /// The posterior point b: row `t_bᵀ(P(u_b) − P(u_a)) q̇ ≥ v_b`.
    Posterior,
}

/// A thigmotaxis row asked of the step pipeline.
#[derive(Clone, Debug, PartialEq)]
pub struct ThigmoRequest {
    /// Index of the contact in the context's self contacts.
    pub contact: usize,
    /// Which strand's row.
    pub strand: Strand,
    /// Target relative sliding speed (cm/s).
    pub speed: f64,
    /// Largest force of the row (dyn).
    pub max_force: f64,
    /// The generalized forces the row may exert: the pipeline confines the row to it.
    pub confinement: Confinement,
}

impl ThigmoParameters {
    /// This phase's actuation `since` seconds after it began: with a [`Replay`], the tail
    /// pull and the replayed field at `since` as joint torques (no rows: no contact
    /// feedback); otherwise [`ThigmoParameters::actuate`].
    pub fn actuate_since(&self, since: f64, context: &ControlContext<'_>, out: &mut Actuation) {
        let Some(replay) = &self.replay else { return self.actuate(context, out) };
        self.actuate_pull(context, out);
        if let Some(field) = &replay.field {
            field.sample(since, &mut out.torques);
        }
    }

    /// Requests the four rows (two when first and last are the same contact) and the tail
    /// pull. Does nothing without self contacts.
    pub fn actuate(&self, context: &ControlContext<'_>, out: &mut Actuation) {
        let contacts = context.self_contacts;
        self.actuate_pull(context, out);
        let Some(last) = contacts.len().checked_sub(1) else { return };
        let confinement = self.force_space.confinement();
        let mut request = |contact, targets: SlidingTargets| {
            for (strand, speed) in
                [(Strand::Anterior, targets.v_a), (Strand::Posterior, targets.v_b)]
            {
                out.thigmo.push(ThigmoRequest {
                    contact,
                    strand,
                    speed,
                    max_force: self.max_force_dyn,
                    confinement: confinement.clone(),
                });
            }
        };
        request(0, self.head);
        if last > 0 {
            request(last, self.tail);
        }
    }
}
