//! # hagfish-control
//!
//! Controllers decide, once per step, forces and dampers on the body (and, for thigmotaxis,
//! constraint rows). They see the state, its kinematics, the centreline and the self contacts
//! through a [`ControlContext`] and write an [`Actuation`]; the step pipeline applies it.
//!
//! - [`WaterDrag`]: implicit linear + quadratic drag on every body.
//! - [`FormingController`]: the scripted knot-forming tail pull (thesis §3.3.1, §5.1).
//! - [`TiePhase`]: a knot tied by control from the body's current state, with the tube it
//!   plans with kept on any body ([`diameters_tail_ward`]); its plan is a [`TiePlan`] of
//!   named steps, each carrying the crossing check that runs after it.
//! - [`PhasedController`]: drag plus a scenario's phases in order.
//!
//! CGS units throughout.
//!
//! A phase's end condition as a knot size in local diameters, so that it carries over to
//! another body: the contact span (the stretch of body the knot's contacts cover) at most
//! 12 mean local diameters D, held for 0.3 s.
//!
//! ```
//! use hagfish_control::{Condition, Direction, KnotSpan, Observation, Quantity, Threshold, Until};
//!
//! // In a scenario file: `until: (seconds: 6.0, hold_s: 0.3, when: [(Span, Below, D(12.0))])`.
//! let small = Condition::new(Quantity::Span, Direction::Below, Threshold::D(12.0))?;
//! let until = Until { seconds: 6.0, hold_s: 0.3, when: vec![small] };
//! let span = |length_cm: f64, diameter_cm: f64| KnotSpan {
//!     start_cm: 10.0,
//!     end_cm: 10.0 + length_cm,
//!     first_contact_cm: 10.0,
//!     last_contact_cm: 10.0,
//!     diameter_cm,
//! };
//! let seen = |span| Observation {
//!     span: Some(span),
//!     body_length_cm: 42.4,
//!     kinetic_energy_erg: 0.0,
//!     core_start_l: None,
//!     core_length_d: None,
//!     core_length_d_at_start: None,
//! };
//! let (tight, loose) = (span(20.0, 1.76), span(25.0, 1.76));
//! let mut since = None;
//! assert!(!until.over(1.0, 1.0, &seen(&loose), &mut since), "25 cm = 14.2 D > 12 D");
//! assert!(!until.over(1.1, 1.1, &seen(&tight), &mut since), "11.4 D, not yet held");
//! assert!(until.over(1.5, 1.5, &seen(&tight), &mut since), "held for 0.4 s ≥ 0.3 s");
//! // On a body a sixth thinner the same 20 cm span is 13.6 D: not tight enough.
//! let mut since = None;
//! assert!(!until.over(1.5, 1.5, &seen(&span(20.0, 1.47)), &mut since));
//! # Ok::<(), hagfish_control::ControlError>(())
//! ```

mod controller;
mod controller_state;
mod crossings;
mod dof_kind;
mod drag;
mod error;
mod follow;
mod force_space;
mod forming;
mod knot_plan;
mod knot_span;
mod load;
mod loops;
mod modal_basis;
mod phases;
mod pull;
mod replay;
mod tail_pd;
mod thigmotaxis;
mod tie;
mod tie_plan;
mod tube_length;
mod until;

pub use controller::{
    Actuation, ControlContext, Controller, Grip, Passive, PointDamper, PointForce, tail_end,
};
pub use controller_state::ControllerState;
pub use crossings::{Crossing, Layer, crossings_of_tail};
pub use dof_kind::{DofKind, KindSelection};
pub use drag::WaterDrag;
pub use error::ControlError;
pub use follow::{FollowPhase, FollowScratch, KnotTemplate, ServoGains};
pub use force_space::{Confinement, ForceSpace, ModalSpace};
pub use forming::{FormingController, FormingScript, ScriptProgress, ScriptStep, Waypoint};
pub use knot_plan::{
    FIGURE_EIGHT, KnotPlan, KnotPlanStep, OVERHAND, PlanAction, PlanCheck, PlanTarget,
};
pub use knot_span::KnotSpan;
pub use load::{LoadDirection, LoadPhase};
pub use loops::{ProjectedLoop, largest_projected_loop};
pub use modal_basis::{ModalBasis, RANK_TOLERANCE};
pub use phases::{
    KnotObservation, Phase, PhaseProgress, PhasedController, ThigmoPhase, TieFailure,
    kinetic_energy,
};
pub use pull::{PullAnchor, PullPhase};
pub use replay::{Replay, ReplayField};
pub use tail_pd::TailGains;
pub use thigmotaxis::{SlidingTargets, Strand, ThigmoParameters, ThigmoRequest};
pub use tie::{
    CrossingCheck, CrossingMiss, HOLD_REACH_BODIES, Handedness, HeldCrossing, LayerCode,
    MAX_HELD_CROSSINGS, MIN_AGREEMENT, PlannedKnot, TieKnot, TiePhase, TieProgress,
};
pub use tie_plan::{PlanStep, TiePlan};
pub use tube_length::{diameters_tail_ward, fraction_leaving};
pub use until::{Condition, Direction, Observation, Quantity, Threshold, Until};
