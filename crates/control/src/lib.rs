//! # hagfish-control
//!
//! Controllers decide, once per step, forces and dampers on the body (and, for thigmotaxis,
//! constraint rows). They see the state, its kinematics, the centreline and the self contacts
//! through a [`ControlContext`] and write an [`Actuation`]; the step pipeline applies it.
//!
//! - [`WaterDrag`]: implicit linear + quadratic drag on every body.
//! - [`FormingController`]: the scripted knot-forming tail pull (thesis §3.3.1, §5.1).
//! - [`TiePhase`]: a knot tied by control from the body's current state.
//! - [`PhasedController`]: drag plus a scenario's phases in order.
//!
//! CGS units throughout.

mod controller;
mod controller_state;
mod drag;
mod error;
mod forming;
mod knot_span;
mod load;
mod loops;
mod phases;
mod tail_pd;
mod thigmotaxis;
mod tie;

pub use controller::{Actuation, ControlContext, Controller, Passive, PointDamper, PointForce};
pub use controller_state::ControllerState;
pub use drag::WaterDrag;
pub use error::ControlError;
pub use forming::{FormingController, FormingScript, ScriptProgress, ScriptStep, Waypoint};
pub use knot_span::KnotSpan;
pub use load::{LoadDirection, LoadPhase};
pub use loops::{ProjectedLoop, largest_projected_loop};
pub use phases::{
    KnotObservation, Observation, Phase, PhaseProgress, PhasedController, ThigmoPhase, TieFailure,
    Until, kinetic_energy,
};
pub use tail_pd::TailGains;
pub use thigmotaxis::{SlidingTargets, Strand, ThigmoParameters, ThigmoRequest};
pub use tie::{Handedness, MIN_AGREEMENT, TieKnot, TiePhase, TieProgress};
