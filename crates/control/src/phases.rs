//! A scenario's controller: water drag on every step plus a sequence of phases, each with its
//! own way of ending (D13: an explicit phase switch, not "first contact").

use std::fmt;

use glam::DVec3;
use hagfish_geometry::SelfContact;
use hagfish_tree::Body;
use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, Controller};
use crate::crossings::{Crossing, Layer, crossings_of_tail};
use crate::drag::WaterDrag;
use crate::follow::{FollowPhase, FollowScratch};
use crate::force_space::Confinement;
use crate::forming::{FormingController, FormingScript, body_at_fraction, body_length};
use crate::knot_span::KnotSpan;
use crate::load::LoadPhase;
use crate::pull::{PullAnchor, PullPhase};
use crate::thigmotaxis::{Strand, ThigmoParameters, ThigmoRequest};
use crate::tie::{
    CrossingCheck, CrossingMiss, HOLD_REACH_BODIES, HeldCrossing, LayerCode, TiePhase, TieProgress,
};
use crate::until::{Observation, Until};

/// One phase of a scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Phase {
    /// Scripted knot forming with the tail; ends when the script's last step has ended
    /// (the target is then held by the next phase only if that phase holds it).
    Form(FormingScript),
    /// Keeps the last forming target (if any) for a time (s); the body is otherwise passive.
    Hold(f64),
    /// Thigmotaxic inverse dynamics on the first and last self contact until a condition.
    Thigmotaxis(ThigmoPhase),
    /// Ties a knot by control from the body's current state ([`TiePhase`]); ends once the
    /// knot analysis shows it, or fails after its attempts.
    Tie(TiePhase),
    /// Puts a load on the tail end ([`LoadPhase`]), which stays on after the phase, until a
    /// condition (e.g. settled).
    Load(LoadPhase),
    /// Ties a knot by following the leader along a template ([`FollowPhase`]); ends once the
    /// knot analysis shows it, or fails `settle_s` after the template without it.
    Follow(FollowPhase),
    /// Grips the tail end and pulls it at a prescribed speed ([`PullPhase`]); after the
    /// phase the grip holds it still, until a later pull.
    Pull(PullPhase),
}

impl Phase {
    /// This phase on a body of `bodies` (head to tail): a tie's crossover placed for that body
    /// ([`TiePhase::on_body`]); any other phase as it is.
    pub fn on_body(&self, bodies: &[Body]) -> Phase {
        match self {
            Phase::Tie(tie) => Phase::Tie(tie.on_body(bodies)),
            Phase::Follow(follow) => Phase::Follow(follow.on_body(bodies)),
            other => other.clone(),
        }
    }

    /// The forming script this phase drives the tail with, if any (a tie phase's plan).
    pub fn script(&self) -> Option<FormingScript> {
        match self {
            Phase::Form(script) => Some(script.clone()),
            Phase::Tie(tie) => Some(tie.script()),
            Phase::Hold(_)
            | Phase::Thigmotaxis(_)
            | Phase::Load(_)
            | Phase::Pull(_)
            | Phase::Follow(_) => None,
        }
    }
}

/// A thigmotaxis phase: its name, parameters and when it ends.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThigmoPhase {
    /// Name shown in the `phase` column of the outputs, e.g. "tighten", "loosen", "slide".
    #[serde(default = "default_thigmo_name")]
    pub name: String,
    /// Targets, tail pull and force cap.
    pub parameters: ThigmoParameters,
    /// When the phase ends.
    pub until: Until,
}

fn default_thigmo_name() -> String {
    "thigmo".to_string()
}

/// The kinetic energy of the body at the start of the step (erg,
/// [`hagfish_tree::kinetic_energy`]).
pub fn kinetic_energy(context: &ControlContext<'_>) -> f64 {
    hagfish_tree::kinetic_energy(context.kinematics)
}

/// What the knot analysis of the body shows at an observation (every `observe_every_s` of
/// the scenario; [`PhasedController::observe_knot`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KnotObservation<'a> {
    /// The knot type's Rolfsen name (`0_1`, `3_1`, …).
    pub name: &'a str,
    /// The fraction of closure directions that agree on it.
    pub agreement: f64,
    /// The handedness of the knotted core (sign of its writhe), if it has one.
    pub right_handed: Option<bool>,
    /// The knotted core's head-ward end (fraction of L), if the frame is knotted.
    pub core_start_l: Option<f64>,
    /// The knotted core's length in local diameters, if the frame is knotted.
    pub core_length_d: Option<f64>,
}

/// Progress through the phases: the controller state a checkpoint must keep.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PhaseProgress {
    /// When the latest load phase so far started (s), or `None` before any: its load stays
    /// on ([`LoadPhase`]).
    #[serde(default)]
    pub load_since: Option<f64>,
    /// The latest pull so far, or `None` before any: its grip stays on ([`PullPhase`]).
    #[serde(default)]
    pub pull: Option<PullAnchor>,
    /// Index of the current phase (`phases.len()` after the last: passive).
    pub phase: usize,
    /// Time the current phase started (s).
    pub started_at: f64,
    /// Since when a condition of the current phase's [`Until`] has held without
    /// interruption (s), or `None`.
    #[serde(default)]
    pub condition_since: Option<f64>,
    /// The knotted core's head-ward end at the latest observation (fraction of L), or
    /// `None` if the body was not knotted then (for [`crate::Quantity::CoreStart`]).
    #[serde(default)]
    pub core_start_l: Option<f64>,
    /// The knotted core's length at the latest observation (local diameters), or `None`
    /// (for [`crate::Quantity::CoreLength`]).
    #[serde(default)]
    pub core_length_d: Option<f64>,
    /// [`PhaseProgress::core_length_d`] when the current phase started
    /// (for [`crate::Quantity::CoreGrowth`] and [`crate::Quantity::CoreShrink`]).
    #[serde(default)]
    pub core_length_d_at_start: Option<f64>,
}

/// Drag plus phases, in order.
#[derive(Clone, Debug)]
pub struct PhasedController {
    drag: Option<WaterDrag>,
    pub(crate) phases: Vec<Phase>,
    pub(crate) progress: PhaseProgress,
    pub(crate) forming: Option<FormingController>,
    pub(crate) tie: TieProgress,
    /// The crossing checks of the current tie attempt's plan, each with the index of the step
    /// after which it runs ([`crate::TiePlan::checks`]); empty outside a tie. Derived from the
    /// phase and `tie.attempt` whenever either changes, so that a step does not build the plan.
    pub(crate) tie_checks: Vec<(usize, CrossingCheck)>,
    /// A follow-the-leader tie's target buffers.
    follow: FollowScratch,
}

/// A tie phase that failed: which knot, after how many attempts, and the latest crossing
/// check that failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TieFailure {
    /// The knot asked for (its Rolfsen name).
    pub knot: String,
    /// Attempts made.
    pub attempts: u32,
    /// The latest failed crossing check, described ("attempt 1: after the threading the
    /// tail's crossings seen from above were under, over; the plan makes over, under, over").
    pub last_miss: Option<String>,
}

impl fmt::Display for TieFailure {
    /// "4_1 after 2 attempts (attempt 2: after the threading …)".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let plural = if self.attempts == 1 { "" } else { "s" };
        write!(f, "{} after {} attempt{plural}", self.knot, self.attempts)?;
        match &self.last_miss {
            Some(miss) => write!(f, " ({miss})"),
            None => Ok(()),
        }
    }
}

impl PhasedController {
    /// A controller at the start of the first phase.
    pub fn new(drag: Option<WaterDrag>, phases: Vec<Phase>) -> Self {
        let forming = phases.first().and_then(Phase::script).map(FormingController::new);
        let tie = match phases.first() {
            Some(Phase::Tie(_) | Phase::Follow(_)) => {
                TieProgress { attempt: 1, ..TieProgress::default() }
            }
            _ => TieProgress::default(),
        };
        let load_since = matches!(phases.first(), Some(Phase::Load(_))).then_some(0.0);
        let progress = PhaseProgress { load_since, ..PhaseProgress::default() };
        let mut controller = Self {
            drag,
            phases,
            progress,
            forming,
            tie,
            tie_checks: Vec::new(),
            follow: FollowScratch::default(),
        };
        controller.refresh_tie_checks();
        controller
    }

    /// Derives [`PhasedController::tie_checks`] from the current phase and tie attempt.
    pub(crate) fn refresh_tie_checks(&mut self) {
        self.tie_checks.clear();
        if let Some(Phase::Tie(phase)) = self.phases.get(self.progress.phase) {
            let plan = phase.plan_for(self.tie.attempt.max(1));
            let checks = plan.steps.into_iter().enumerate();
            self.tie_checks.extend(checks.filter_map(|(k, step)| step.check.map(|c| (k, c))));
        }
    }

    /// Takes the knot analysis of an observation at time `t` (`None` if it failed). Its
    /// core's head-ward end and length are kept for the core conditions of an [`Until`]
    /// ([`crate::Quantity`]). A tie phase ends on it (the knot shown for `hold_s`), or starts
    /// its plan again, or fails (`settle_s` after its plan without the knot).
    pub fn observe_knot(&mut self, t: f64, knot: Option<KnotObservation<'_>>) {
        self.progress.core_start_l = knot.and_then(|k| k.core_start_l);
        self.progress.core_length_d = knot.and_then(|k| k.core_length_d);
        let (shown, settle_s) = match self.phases.get(self.progress.phase) {
            Some(Phase::Tie(phase)) => (
                knot.is_some_and(|k| phase.knot.is_shown_by(k.name, k.agreement, k.right_handed)),
                phase.settle_s,
            ),
            Some(Phase::Follow(phase)) => (
                knot.is_some_and(|k| {
                    phase.template.is_shown_by(k.name, k.agreement, k.right_handed)
                }),
                phase.settle_s,
            ),
            _ => return,
        };
        self.tie.shown_since = if shown { Some(self.tie.shown_since.unwrap_or(t)) } else { None };
        let late = self.tie.plan_done_at.is_some_and(|done| t - done >= settle_s);
        if shown || !late || self.tie.failed {
            return;
        }
        let Some(Phase::Tie(phase)) = self.phases.get(self.progress.phase) else {
            self.tie.failed = true;
            return;
        };
        if self.tie.attempt >= phase.attempts {
            self.tie.failed = true;
        } else {
            self.tie = TieProgress {
                attempt: self.tie.attempt + 1,
                last_miss: self.tie.last_miss,
                ..TieProgress::default()
            };
            self.forming = Some(FormingController::new(phase.script_for(self.tie.attempt)));
            self.refresh_tie_checks();
        }
    }

    /// Runs the tie phase's crossing checks whose step has ended ([`crate::PlanStep::check`])
    /// on the body's crossings seen from above, from the crossover on.
    fn check_crossings(&mut self, context: &ControlContext<'_>) {
        let Some(Phase::Tie(phase)) = self.phases.get(self.progress.phase) else {
            return;
        };
        if self.crossing_check_due().is_none() {
            return;
        }
        let centres: Vec<DVec3> =
            (0..context.model.body_count()).map(|i| context.centre(i)).collect();
        let found = crossings_of_tail(&centres, body_at_fraction(context, phase.at), DVec3::Z);
        self.observe_crossings(&found);
    }

    /// A hold row ([`TiePhase::hold_crossings_dyn`]) on the self contact at each held
    /// crossing: the contact within [`HOLD_REACH_BODIES`] of where the crossing was on both
    /// strands, the nearest (in the larger of the two distances), which the crossing then
    /// follows. A crossing without such a contact (its strands apart) is not held this step.
    fn hold_crossings(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        let Some(Phase::Tie(phase)) = self.phases.get(self.progress.phase) else {
            return;
        };
        let Some(max_force) = phase.hold_crossings_dyn else {
            return;
        };
        for held in self.tie.held.iter_mut().flatten() {
            let distance =
                |c: &SelfContact| (c.u_a - held.other_u).abs().max((c.u_b - held.tail_u).abs());
            let nearest = context
                .self_contacts
                .iter()
                .enumerate()
                .map(|(k, c)| (k, distance(c)))
                .filter(|&(_, d)| d <= HOLD_REACH_BODIES)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            let Some((k, _)) = nearest else { continue };
            let contact = &context.self_contacts[k];
            *held = HeldCrossing { tail_u: contact.u_b, other_u: contact.u_a };
            if out.thigmo.iter().all(|request| request.contact != k) {
                out.thigmo.push(ThigmoRequest {
                    contact: k,
                    strand: Strand::Posterior,
                    speed: 0.0,
                    max_force,
                    confinement: Confinement::Full,
                });
            }
        }
    }

    /// The tie phase's next crossing check, if the plan step carrying it has ended.
    fn crossing_check_due(&self) -> Option<&CrossingCheck> {
        let Some(Phase::Tie(_)) = self.phases.get(self.progress.phase) else {
            return None;
        };
        let step = self.forming.as_ref()?.progress().step;
        let (after_step, check) = self.tie_checks.get(self.tie.checks_done as usize)?;
        (step > *after_step && !self.tie.failed).then_some(check)
    }

    /// Runs the due crossing checks on the crossings `found`. A failed check is recorded
    /// ([`TieProgress::last_miss`]) and ends the checking of this attempt; the attempt itself
    /// ends as before, on the knot analysis: a check is a diagnosis, the analysis the judge.
    /// A check that passes on the crossings themselves starts holding those it checked, when
    /// the phase holds crossings.
    pub(crate) fn observe_crossings(&mut self, found: &[Crossing]) {
        let layers: Vec<Layer> = found.iter().map(|c| c.layer).collect();
        let holds = matches!(
            self.phases.get(self.progress.phase),
            Some(Phase::Tie(TiePhase { hold_crossings_dyn: Some(_), .. }))
        );
        while let Some(check) = self.crossing_check_due() {
            if check.is_met_by(&layers) {
                let checked = check.expected.len();
                for (slot, crossing) in self.tie.held.iter_mut().zip(&found[..checked]) {
                    if holds && slot.is_none() {
                        *slot = Some(HeldCrossing {
                            tail_u: crossing.tail_u,
                            other_u: crossing.other_u,
                        });
                    }
                }
                self.tie.checks_done += 1;
                continue;
            }
            if self.tie.shown_since.is_some() {
                self.tie.checks_done += 1;
                continue;
            }
            self.tie.last_miss = Some(CrossingMiss {
                attempt: self.tie.attempt,
                check: self.tie.checks_done,
                found: LayerCode::of(&layers),
            });
            self.tie.checks_done = self.tie_checks.len() as u32;
        }
    }

    /// The failed tie phase, if the current phase is one.
    pub fn tie_failure(&self) -> Option<TieFailure> {
        match self.phases.get(self.progress.phase) {
            Some(Phase::Tie(phase)) if self.tie.failed => Some(TieFailure {
                knot: phase.knot.name().to_string(),
                attempts: self.tie.attempt,
                last_miss: self.tie.last_miss.map(|miss| Self::describe(phase, miss)),
            }),
            Some(Phase::Follow(phase)) if self.tie.failed => {
                Some(TieFailure { knot: phase.template.knot.clone(), attempts: 1, last_miss: None })
            }
            _ => None,
        }
    }

    /// A crossing miss in words, with the check's name and what the plan makes.
    fn describe(phase: &TiePhase, miss: CrossingMiss) -> String {
        let plan = phase.plan_for(miss.attempt);
        let check = plan.checks().nth(miss.check as usize);
        let (name, expected) = check.map_or(("a check", String::new()), |(_, c)| {
            (c.name.as_str(), LayerCode::of(&c.expected).to_string())
        });
        format!(
            "attempt {}: after {name} the tail's crossings seen from above were {}; the plan makes {expected}",
            miss.attempt, miss.found
        )
    }

    /// Where the controller is.
    pub fn progress(&self) -> &PhaseProgress {
        &self.progress
    }

    /// A short name of the current phase for tables: "form", "hold", "tie" (either kind of
    /// tie), "load", the thigmotaxis phase's name, or "done".
    pub fn phase_name(&self) -> &str {
        match self.phases.get(self.progress.phase) {
            Some(Phase::Form(_)) => "form",
            Some(Phase::Hold(_)) => "hold",
            Some(Phase::Thigmotaxis(phase)) => &phase.name,
            Some(Phase::Tie(_) | Phase::Follow(_)) => "tie",
            Some(Phase::Load(_)) => "load",
            Some(Phase::Pull(_)) => "pull",
            None => "done",
        }
    }

    /// True when the current phase is over; for thigmotaxis, also notes since when a knot
    /// condition has held.
    fn phase_over(&mut self, context: &ControlContext<'_>) -> bool {
        let t = context.state.t;
        let elapsed = t - self.progress.started_at;
        match self.phases.get(self.progress.phase) {
            Some(Phase::Form(_)) => self.forming.as_ref().is_none_or(FormingController::finished),
            Some(Phase::Hold(seconds)) => elapsed >= *seconds,
            Some(
                Phase::Thigmotaxis(ThigmoPhase { until, .. })
                | Phase::Load(LoadPhase { until, .. })
                | Phase::Pull(PullPhase { until, .. }),
            ) => {
                let span = KnotSpan::of(context.self_contacts, context.centreline);
                let observed = Observation {
                    span: span.as_ref(),
                    body_length_cm: body_length(context),
                    kinetic_energy_erg: kinetic_energy(context),
                    core_start_l: self.progress.core_start_l,
                    core_length_d: self.progress.core_length_d,
                    core_length_d_at_start: self.progress.core_length_d_at_start,
                };
                until.over(t, elapsed, &observed, &mut self.progress.condition_since)
            }
            Some(
                Phase::Tie(TiePhase { hold_s, .. }) | Phase::Follow(FollowPhase { hold_s, .. }),
            ) => self.tie.shown_since.is_some_and(|s| t - s >= *hold_s),
            None => false,
        }
    }

    fn advance(&mut self, t: f64) {
        if let Some(pull) = self.progress.pull.as_mut().filter(|p| p.phase == self.progress.phase) {
            pull.stopped_s = Some(t);
        }
        let phase = self.progress.phase + 1;
        let load_since = match self.phases.get(phase) {
            Some(Phase::Load(_)) => Some(t),
            _ => self.progress.load_since,
        };
        self.progress = PhaseProgress {
            phase,
            started_at: t,
            condition_since: None,
            load_since,
            core_length_d_at_start: self.progress.core_length_d,
            ..self.progress
        };
        if let Some(script) = self.phases.get(self.progress.phase).and_then(Phase::script) {
            self.forming = Some(FormingController::new(script));
        }
        self.tie = match self.phases.get(self.progress.phase) {
            Some(Phase::Tie(_) | Phase::Follow(_)) => {
                TieProgress { attempt: 1, ..TieProgress::default() }
            }
            _ => TieProgress::default(),
        };
        self.refresh_tie_checks();
    }
}

impl Controller for PhasedController {
    fn control(&mut self, context: &ControlContext<'_>, out: &mut Actuation) {
        if let Some(drag) = &mut self.drag {
            drag.control(context, out);
        }
        while self.progress.phase < self.phases.len() && self.phase_over(context) {
            self.advance(context.state.t);
        }
        match self.phases.get(self.progress.phase) {
            Some(Phase::Form(_) | Phase::Hold(_)) => {
                if let Some(forming) = &mut self.forming {
                    forming.control(context, out);
                }
            }
            Some(Phase::Tie(_)) => {
                if let Some(forming) = &mut self.forming {
                    forming.control(context, out);
                    if forming.finished() && self.tie.plan_done_at.is_none() {
                        self.tie.plan_done_at = Some(context.state.t);
                    }
                }
                self.check_crossings(context);
                self.hold_crossings(context, out);
            }
            Some(Phase::Thigmotaxis(phase)) => {
                let since = context.state.t - self.progress.started_at;
                phase.parameters.actuate_since(since, context, out);
            }
            Some(Phase::Follow(phase)) => {
                let elapsed = context.state.t - self.progress.started_at;
                phase.actuate(elapsed, context, &mut self.follow, out);
                if phase.followed_all(elapsed) && self.tie.plan_done_at.is_none() {
                    self.tie.plan_done_at = Some(context.state.t);
                }
            }
            Some(Phase::Pull(pull)) => {
                let phase = self.progress.phase;
                if self.progress.pull.is_none_or(|anchor| anchor.phase != phase) {
                    self.progress.pull = Some(PullAnchor::start(pull, phase, context));
                }
            }
            Some(Phase::Load(_)) | None => {}
        }
        if let Some((load, since)) = self.active_load() {
            load.actuate(since, context, out);
        }
        out.grip = self.progress.pull.map(|anchor| anchor.grip(context));
    }
}

impl PhasedController {
    /// The latest load phase up to the current one and when it started, if any.
    fn active_load(&self) -> Option<(&LoadPhase, f64)> {
        let since = self.progress.load_since?;
        let upto = (self.progress.phase + 1).min(self.phases.len());
        self.phases[..upto].iter().rev().find_map(|phase| match phase {
            Phase::Load(load) => Some((load, since)),
            _ => None,
        })
    }

    /// True once every phase is over (the body is then passive, but for a load that stays).
    pub fn finished(&self) -> bool {
        self.progress.phase >= self.phases.len()
    }

    /// The phase still running, as a reader should see it at the end of a run, or `None`
    /// when every phase is over: its name, and for a tie phase the knot that is not tied yet
    /// and the attempt (`tie (3_1 not tied, attempt 1 of 2)`).
    pub fn unfinished_phase(&self) -> Option<String> {
        match self.phases.get(self.progress.phase)? {
            Phase::Follow(phase) => {
                Some(format!("tie ({} not tied, following its template)", phase.template.knot))
            }
            Phase::Tie(phase) => {
                let miss = self.tie.last_miss.map(|m| format!("; {}", Self::describe(phase, m)));
                Some(format!(
                    "tie ({} not tied, attempt {} of {}{})",
                    phase.knot.name(),
                    self.tie.attempt,
                    phase.attempts,
                    miss.unwrap_or_default()
                ))
            }
            _ => Some(self.phase_name().to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_latest_frames_core_is_kept_in_any_phase_and_forgotten_when_unknotted() {
        let mut controller = PhasedController::new(None, vec![Phase::Hold(1.0)]);
        let knot = KnotObservation {
            name: "3_1",
            agreement: 1.0,
            right_handed: Some(true),
            core_start_l: Some(0.3),
            core_length_d: Some(14.0),
        };
        controller.observe_knot(0.5, Some(knot));
        assert_eq!(controller.progress().core_start_l, Some(0.3), "kept in any phase");
        controller.advance(1.0);
        assert_eq!(controller.progress().core_start_l, Some(0.3), "and across phases");
        assert_eq!(controller.progress().core_length_d, Some(14.0));
        controller.observe_knot(1.1, None);
        assert_eq!(controller.progress().core_start_l, None, "a failed analysis forgets it");
        assert_eq!(controller.progress().core_length_d, None);
    }

    #[test]
    fn the_unfinished_phase_is_named_and_a_tie_says_its_knot_and_attempt() {
        let tie = TiePhase::new(crate::tie::TieKnot::Trefoil(crate::tie::Handedness::Right), 0.31);
        let mut controller = PhasedController::new(None, vec![Phase::Tie(tie), Phase::Hold(1.0)]);
        let unfinished = controller.unfinished_phase();
        assert_eq!(unfinished.as_deref(), Some("tie (3_1 not tied, attempt 1 of 2)"));
        controller.advance(10.0);
        assert_eq!(controller.unfinished_phase().as_deref(), Some("hold"));
        controller.advance(11.0);
        assert_eq!(controller.unfinished_phase(), None, "every phase over");
    }
}
