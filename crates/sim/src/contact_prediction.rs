//! Contact prediction: the self-contact rows bound the gap to first order,
//! `g + h·nᵀ(ẋ_b − ẋ_a) ≥ g_target`, but the gap at the end of the step is a nonlinear function of
//! `q + h q̇`: body rotations curve the paths of the contact points, and where two curved strands
//! slide past each other the closest points move along them. At h = 0.01 s with strands sliding at
//! 2–4 cm/s that second-order error reached 2.1 % of the radius (`docs/physics.md`).
//!
//! The predictor evaluates the gap after the step exactly, `g⁺ = |x_b⁺ − x_a⁺| − r_a − r_b`, at the
//! closest points near the contact's parameters on the centreline of the predicted positions
//! `q⁺ = q + h q̇` ([`hagfish_geometry::closest_points_near`]). Where `g⁺` falls below the row's
//! target `g_target = g + h·b(g)` (0 for an open contact; `(1 − β)g` for a penetration pushed out
//! by the fraction β) by more than the tolerance, the row's bound becomes
//!
//! `b ← max(b, v + min(g_target − g⁺, MAX_CORRECTION)/h)`, with `v = nᵀ(ẋ_b − ẋ_a)` the
//! achieved normal speed,
//!
//! the normal speed that, to first order in the correction, lifts `g⁺` to `g_target`; the step is
//! then solved again with the same M̃ and rows (a predictor–corrector on the bounds, as the
//! joint-limit rows added for overshooting joints). The raised bounds are the step's own copy
//! of the right-hand sides; the rows keep the first-order ones. The pipeline predicts after the
//! first solve of a step only and solves with the rows' own bounds if the raised ones leave no
//! solution (`pipeline::solve_and_resolve`).

use glam::DVec3;
use hagfish_geometry::{Centreline, SelfContact, closest_points_near};
use hagfish_solver::{RowKind, Rows};
use hagfish_tree::{Data, Model, State};

use crate::options::StepOptions;
use crate::rows::RowGroup;
use crate::rows::unilateral_rhs;
use crate::skin::SkinLayer;

/// cos of the largest angle between a contact's normal and the line between the predicted
/// closest points for the prediction to count (25°).
const NORMAL_AGREEMENT: f64 = 0.9;

/// Largest correction of one row's gap per step (cm, ≈ 2.5 % of the ES103 radius): above the
/// largest one-step second-order error seen (0.013 cm); a larger predicted shortfall means the
/// prediction left the contact's basin.
const MAX_CORRECTION: f64 = 0.02;

/// Scratch of the contact predictor: the predicted positions, their kinematics and centreline.
#[derive(Debug)]
pub(crate) struct ContactPredictor {
    q: Vec<f64>,
    kinematics: Data,
    centres: Vec<DVec3>,
    radii: Vec<f64>,
    centreline: Centreline,
}

impl ContactPredictor {
    /// Buffers for `model`; `centreline` (a centreline of the model, tube radii included) is
    /// the starting value of the predicted one, whose radii are those of the cores where
    /// `skin` has a skin (the contact rows hold the cores apart).
    pub(crate) fn new(model: &Model, centreline: &Centreline, skin: &SkinLayer) -> Self {
        Self {
            q: vec![0.0; model.dof_count()],
            kinematics: Data::new(model),
            centres: vec![DVec3::ZERO; model.body_count()],
            radii: skin.core_radii(centreline.radii()),
            centreline: centreline.clone(),
        }
    }

    /// Raises, in `bounds` (one per row of `rows`), the bound of each self-contact row (source
    /// [`RowGroup::Contact`], id its contact in `contacts`) whose gap after the step with
    /// velocity `qdot` would fall more than the tolerance of
    /// [`StepOptions::contact_prediction`] below the row's target (module docs; nothing when
    /// that option is `None`). Returns how many bounds were raised.
    #[allow(clippy::too_many_arguments)] // the stage's inputs, each read once
    pub(crate) fn tighten_contact_bounds(
        &mut self,
        model: &Model,
        options: &StepOptions,
        state: &State,
        qdot: &[f64],
        contacts: &[SelfContact],
        skin: &SkinLayer,
        rows: &Rows,
        bounds: &mut [f64],
    ) -> usize {
        let Some(tolerance) = options.contact_prediction else { return 0 };
        let (time_step, push_out) = (options.time_step, options.push_out);
        let contact_tag = RowGroup::Contact.tag();
        if !rows.sources().iter().any(|s| s.tag == contact_tag)
            || !self.predict_centreline(model, state, qdot, time_step)
        {
            return 0;
        }
        let mut raised_count = 0;
        // A contact's rows (its normal or its pyramid's edges) are consecutive and share its
        // predicted gap: searched once per contact.
        let mut last_gap: Option<(usize, f64)> = None;
        for (row, source) in rows.sources().iter().enumerate() {
            let contact = match contacts.get(source.id) {
                // An exact cone's friction rows bound the slip, not the gap.
                _ if matches!(rows.kinds()[row], RowKind::Friction { .. }) => continue,
                Some(contact) if source.tag == contact_tag => contact,
                _ => continue,
            };
            let gap_after = match last_gap {
                Some((id, gap)) if id == source.id => gap,
                _ => self.gap_after(contact),
            };
            last_gap = Some((source.id, gap_after));
            let core_gap = skin.core_gap(contact);
            let target = core_gap + time_step * unilateral_rhs(core_gap, time_step, push_out);
            if gap_after >= target - tolerance {
                continue;
            }
            let Some(coefficients) = rows.row(row) else { continue };
            let speed: f64 = coefficients.iter().zip(qdot).map(|(c, v)| c * v).sum();
            let raised = speed + (target - gap_after).min(MAX_CORRECTION) / time_step;
            if raised > bounds[row] {
                bounds[row] = raised;
                raised_count += 1;
            }
        }
        raised_count
    }

    /// The gap of `contact` on the predicted centreline: at the closest points near its
    /// parameters ([`closest_points_near`]) if the line between them is within
    /// [`NORMAL_AGREEMENT`] of the row's normal (so that pushing along the row's normal opens
    /// that gap too), otherwise between the contact's own material points. (The first can be
    /// a body or more away along the strands: where a strand end lies cradled along another
    /// strand the distance is flat and the closest point jumps; merging keeps one record per
    /// such stretch.)
    fn gap_after(&self, contact: &SelfContact) -> f64 {
        let line = &self.centreline;
        let near = closest_points_near(line, contact.u_a, contact.u_b);
        let (x_a, x_b) = (line.point(near.u_a), line.point(near.u_b));
        let aligned = (x_b - x_a).normalize_or_zero().dot(contact.normal) >= NORMAL_AGREEMENT;
        let (u_a, u_b, distance) = if aligned {
            (near.u_a, near.u_b, near.distance)
        } else {
            let (u_a, u_b) = (contact.u_a, contact.u_b);
            (u_a, u_b, line.point(u_a).distance(line.point(u_b)))
        };
        distance - line.radius(u_a) - line.radius(u_b)
    }

    /// The centreline through the body centres at `q + h q̇`; false (no prediction) if those
    /// centres give no centreline (non-finite velocities, which the integrator reports).
    fn predict_centreline(&mut self, model: &Model, state: &State, qdot: &[f64], h: f64) -> bool {
        for ((predicted, q), v) in self.q.iter_mut().zip(&state.q).zip(qdot) {
            *predicted = q + h * v;
        }
        hagfish_tree::frame_kinematics(model, &self.q, &mut self.kinematics);
        for (i, centre) in self.centres.iter_mut().enumerate() {
            *centre = self.kinematics.body_centre(i);
        }
        self.centreline.update(&self.centres, &self.radii).is_ok()
    }
}
