//! A scenario's controller: water drag on every step plus a sequence of phases, each with its
//! own way of ending (D13: an explicit phase switch, not "first contact").

use serde::{Deserialize, Serialize};

use crate::controller::{Actuation, ControlContext, Controller};
use crate::drag::WaterDrag;
use crate::forming::{FormingController, FormingScript, body_length};
use crate::knot_span::KnotSpan;
use crate::load::LoadPhase;
use crate::thigmotaxis::ThigmoParameters;
use crate::tie::{TieKnot, TiePhase, TieProgress};

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
}

impl Phase {
    /// The forming script this phase drives the tail with, if any (a tie phase's plan).
    pub fn script(&self) -> Option<FormingScript> {
        match self {
            Phase::Form(script) => Some(script.clone()),
            Phase::Tie(tie) => Some(tie.script()),
            Phase::Hold(_) | Phase::Thigmotaxis(_) | Phase::Load(_) => None,
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

/// End conditions of a phase; it ends at the first that holds. The knot conditions read the
/// self contacts of the step ([`KnotSpan`]) and must hold without interruption for
/// `hold_s`; without contacts only the duration counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Until {
    /// Longest duration (s).
    pub seconds: f64,
    /// How long a knot condition must hold without interruption before the phase ends (s,
    /// default 0: at the first step it holds). The contact span flickers by 1–2 cm between
    /// steps as contacts at the knot's ends appear and vanish at the margin; a few tenths of a
    /// second keep one flicker from ending a phase.
    #[serde(default)]
    pub hold_s: f64,
    /// Ends once the knot's anterior end is this close to the head (cm of arc length).
    #[serde(default)]
    pub knot_start_below_cm: Option<f64>,
    /// Ends once the knot's anterior end is this far from the head (cm; sliding tail-ward).
    #[serde(default)]
    pub knot_start_above_cm: Option<f64>,
    /// Ends once the knot's span (contact stretch, cm) is at most this (tightening).
    #[serde(default)]
    pub span_below_cm: Option<f64>,
    /// Ends once the knot's span (contact stretch, cm) is at least this (loosening).
    #[serde(default)]
    pub span_above_cm: Option<f64>,
    /// [`Until::knot_start_below_cm`] as a fraction of the body length L (body-relative:
    /// carries over to other bodies).
    #[serde(default)]
    pub knot_start_below_l: Option<f64>,
    /// [`Until::knot_start_above_cm`] as a fraction of L.
    #[serde(default)]
    pub knot_start_above_l: Option<f64>,
    /// [`Until::span_below_cm`] as a fraction of L.
    #[serde(default)]
    pub span_below_l: Option<f64>,
    /// [`Until::span_above_cm`] as a fraction of L.
    #[serde(default)]
    pub span_above_l: Option<f64>,
    /// [`Until::span_below_cm`] in mean local diameters D over the span
    /// ([`KnotSpan::length_d`]): a knot size that carries over to bodies of other lengths
    /// and thicknesses.
    #[serde(default)]
    pub span_below_d: Option<f64>,
    /// [`Until::span_above_cm`] in mean local diameters D over the span.
    #[serde(default)]
    pub span_above_d: Option<f64>,
    /// Ends once the knotted core's head-ward end is within this fraction of L of the head:
    /// the core (shortest knotted sub-arc, `hagfish_knots`) of the latest recorded frame, so
    /// it is looked at every `record_every_s`. Unlike [`Until::knot_start_below_l`] (the
    /// first self contact, which a loop of the tail end can make near the head while the
    /// knot is still far from it), this is where the knot itself is.
    #[serde(default)]
    pub core_start_below_l: Option<f64>,
    /// Ends once the knotted core (of the latest recorded frame, as
    /// [`Until::core_start_below_l`]) is at least this many local diameters long: loosened.
    #[serde(default)]
    pub core_length_above_d: Option<f64>,
    /// Ends once the knotted core is at most this many local diameters long: tightened.
    #[serde(default)]
    pub core_length_below_d: Option<f64>,
    /// Ends once the knotted core is this fraction longer than when the phase started (0.3:
    /// 30 % longer): loosened relative to the knot the phase was given, whatever its size.
    #[serde(default)]
    pub core_growth_above: Option<f64>,
    /// Ends once the knotted core is this fraction shorter than when the phase started (0.25:
    /// a quarter shorter): tightened relative to the knot the phase was given.
    #[serde(default)]
    pub core_shrink_above: Option<f64>,
    /// Ends once the kinetic energy `½ Σ Vᵢ·IᵢVᵢ` is at most this (erg = g·cm²/s²) for
    /// `hold_s`: the body has settled.
    #[serde(default)]
    pub kinetic_energy_below_erg: Option<f64>,
}

/// What a phase's end conditions look at, at the start of a step.
#[derive(Clone, Copy, Debug)]
pub struct Observation<'a> {
    /// The knot's contact span, if there are self contacts.
    pub span: Option<&'a KnotSpan>,
    /// The body length L (cm).
    pub body_length_cm: f64,
    /// The kinetic energy (erg).
    pub kinetic_energy_erg: f64,
    /// The knotted core's head-ward end at the latest recorded frame (fraction of L), if
    /// that frame was knotted.
    pub core_start_l: Option<f64>,
    /// The knotted core's length at the latest recorded frame in local diameters, if that
    /// frame was knotted.
    pub core_length_d: Option<f64>,
    /// The core's length (local diameters) at the last frame before the phase started.
    pub core_length_d_at_start: Option<f64>,
}

/// The kinetic energy of the body at the start of the step (erg,
/// [`hagfish_tree::kinetic_energy`]).
pub fn kinetic_energy(context: &ControlContext<'_>) -> f64 {
    hagfish_tree::kinetic_energy(context.kinematics)
}

impl Until {
    /// Whether a phase that started `elapsed` seconds ago is over at time `t` given what is
    /// `observed`: its duration has passed, or a knot or settle condition has held since
    /// `since` for at least `hold_s`. Updates `since` (the phase's
    /// [`PhaseProgress::condition_since`]): set when a condition starts to hold, cleared when
    /// none holds.
    pub fn over(
        &self,
        t: f64,
        elapsed: f64,
        observed: &Observation<'_>,
        since: &mut Option<f64>,
    ) -> bool {
        let settled =
            self.kinetic_energy_below_erg.is_some_and(|e| observed.kinetic_energy_erg <= e);
        let core_near_head = self
            .core_start_below_l
            .zip(observed.core_start_l)
            .is_some_and(|(limit, start)| start <= limit);
        let core_length = |limit: Option<f64>, reached: fn(f64, f64) -> bool| {
            limit.zip(observed.core_length_d).is_some_and(|(limit, d)| reached(d, limit))
        };
        let now_and_start = observed.core_length_d.zip(observed.core_length_d_at_start);
        let changed = |fraction: Option<f64>, reached: fn(f64, f64, f64) -> bool| {
            fraction.zip(now_and_start).is_some_and(|(f, (now, start))| reached(now, start, f))
        };
        let loosened = core_length(self.core_length_above_d, |d, limit| d >= limit)
            || changed(self.core_growth_above, |now, start, f| now >= (1.0 + f) * start);
        let tightened = core_length(self.core_length_below_d, |d, limit| d <= limit)
            || changed(self.core_shrink_above, |now, start, f| now <= (1.0 - f) * start);
        let holds = settled
            || core_near_head
            || loosened
            || tightened
            || self.knot_condition(observed.span, observed.body_length_cm);
        *since = if holds { Some(since.unwrap_or(t)) } else { None };
        elapsed >= self.seconds || since.is_some_and(|since| t - since >= self.hold_s)
    }

    /// True once a knot condition holds for the knot at `span` on a body of length
    /// `body_length_cm` (the duration and `hold_s` are not looked at).
    fn knot_condition(&self, span: Option<&KnotSpan>, body_length_cm: f64) -> bool {
        let at_most = |limit: Option<f64>, value: Option<f64>| {
            limit.zip(value).is_some_and(|(limit, value)| value <= limit)
        };
        let at_least = |limit: Option<f64>, value: Option<f64>| {
            limit.zip(value).is_some_and(|(limit, value)| value >= limit)
        };
        let start = span.map(|s| s.start_cm);
        let length = span.map(KnotSpan::length_cm);
        let length_d = span.map(KnotSpan::length_d);
        let of_l = |limit: Option<f64>| limit.map(|fraction| fraction * body_length_cm);
        at_most(self.knot_start_below_cm, start)
            || at_least(self.knot_start_above_cm, start)
            || at_most(self.span_below_cm, length)
            || at_least(self.span_above_cm, length)
            || at_most(of_l(self.knot_start_below_l), start)
            || at_least(of_l(self.knot_start_above_l), start)
            || at_most(of_l(self.span_below_l), length)
            || at_least(of_l(self.span_above_l), length)
            || at_most(self.span_below_d, length_d)
            || at_least(self.span_above_d, length_d)
    }
}

/// What the knot analysis of a recorded frame shows ([`PhasedController::observe_knot`]).
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
    /// Index of the current phase (`phases.len()` after the last: passive).
    pub phase: usize,
    /// Time the current phase started (s).
    pub started_at: f64,
    /// Since when a knot condition of the current phase's [`Until`] has held without
    /// interruption (s), or `None`.
    #[serde(default)]
    pub condition_since: Option<f64>,
    /// The knotted core's head-ward end at the latest recorded frame (fraction of L), or
    /// `None` if that frame was not knotted ([`Until::core_start_below_l`]).
    #[serde(default)]
    pub core_start_l: Option<f64>,
    /// The knotted core's length at the latest recorded frame (local diameters), or `None`
    /// ([`Until::core_length_above_d`], [`Until::core_length_below_d`]).
    #[serde(default)]
    pub core_length_d: Option<f64>,
    /// [`PhaseProgress::core_length_d`] when the current phase started
    /// ([`Until::core_growth_above`], [`Until::core_shrink_above`]).
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
}

/// A tie phase that failed: which knot, after how many attempts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TieFailure {
    /// The knot asked for.
    pub knot: TieKnot,
    /// Attempts made.
    pub attempts: u32,
}

impl PhasedController {
    /// A controller at the start of the first phase.
    pub fn new(drag: Option<WaterDrag>, phases: Vec<Phase>) -> Self {
        let forming = phases.first().and_then(Phase::script).map(FormingController::new);
        let tie = match phases.first() {
            Some(Phase::Tie(_)) => TieProgress { attempt: 1, ..TieProgress::default() },
            _ => TieProgress::default(),
        };
        let load_since = matches!(phases.first(), Some(Phase::Load(_))).then_some(0.0);
        let progress = PhaseProgress { load_since, ..PhaseProgress::default() };
        Self { drag, phases, progress, forming, tie }
    }

    /// Takes the knot analysis of a recorded frame at time `t` (`None` if it failed). Its
    /// core's head-ward end and length are kept for [`Until::core_start_below_l`] and the core
    /// length conditions. A tie phase ends on it (the knot shown for `hold_s`), or starts its
    /// plan again, or fails (`settle_s` after its plan without the knot).
    pub fn observe_knot(&mut self, t: f64, knot: Option<KnotObservation<'_>>) {
        self.progress.core_start_l = knot.and_then(|k| k.core_start_l);
        self.progress.core_length_d = knot.and_then(|k| k.core_length_d);
        let Some(Phase::Tie(phase)) = self.phases.get(self.progress.phase) else {
            return;
        };
        let shown =
            knot.is_some_and(|k| phase.knot.is_shown_by(k.name, k.agreement, k.right_handed));
        self.tie.shown_since = if shown { Some(self.tie.shown_since.unwrap_or(t)) } else { None };
        let late = self.tie.plan_done_at.is_some_and(|done| t - done >= phase.settle_s);
        if shown || !late || self.tie.failed {
            return;
        }
        if self.tie.attempt >= phase.attempts {
            self.tie.failed = true;
        } else {
            self.tie = TieProgress { attempt: self.tie.attempt + 1, ..TieProgress::default() };
            self.forming = Some(FormingController::new(phase.script()));
        }
    }

    /// The failed tie phase, if the current phase is one.
    pub fn tie_failure(&self) -> Option<TieFailure> {
        match self.phases.get(self.progress.phase) {
            Some(Phase::Tie(phase)) if self.tie.failed => {
                Some(TieFailure { knot: phase.knot, attempts: self.tie.attempt })
            }
            _ => None,
        }
    }

    /// Where the controller is.
    pub fn progress(&self) -> &PhaseProgress {
        &self.progress
    }

    /// A short name of the current phase for tables: "form", "hold", the thigmotaxis phase's
    /// name, or "done".
    pub fn phase_name(&self) -> &str {
        match self.phases.get(self.progress.phase) {
            Some(Phase::Form(_)) => "form",
            Some(Phase::Hold(_)) => "hold",
            Some(Phase::Thigmotaxis(phase)) => &phase.name,
            Some(Phase::Tie(_)) => "tie",
            Some(Phase::Load(_)) => "load",
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
                | Phase::Load(LoadPhase { until, .. }),
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
            Some(Phase::Tie(phase)) => self.tie.shown_since.is_some_and(|s| t - s >= phase.hold_s),
            None => false,
        }
    }

    fn advance(&mut self, t: f64) {
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
            Some(Phase::Tie(_)) => TieProgress { attempt: 1, ..TieProgress::default() },
            _ => TieProgress::default(),
        };
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
            }
            Some(Phase::Thigmotaxis(phase)) => phase.parameters.actuate(context, out),
            Some(Phase::Load(_)) | None => {}
        }
        if let Some((load, since)) = self.active_load() {
            load.actuate(since, context, out);
        }
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
            Phase::Tie(phase) => Some(format!(
                "tie ({} not tied, attempt {} of {})",
                phase.knot.name(),
                self.tie.attempt,
                phase.attempts
            )),
            _ => Some(self.phase_name().to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seen(span: Option<&KnotSpan>) -> Observation<'_> {
        Observation {
            span,
            body_length_cm: 40.0,
            kinetic_energy_erg: 1.0,
            core_start_l: None,
            core_length_d: None,
            core_length_d_at_start: None,
        }
    }

    fn span(start_cm: f64, end_cm: f64) -> KnotSpan {
        KnotSpan {
            start_cm,
            end_cm,
            first_contact_cm: start_cm,
            last_contact_cm: start_cm,
            diameter_cm: 2.0,
        }
    }

    #[test]
    fn until_ends_at_the_first_condition_that_holds() {
        let until = Until {
            seconds: 5.0,
            hold_s: 0.0,
            knot_start_below_cm: Some(3.0),
            knot_start_above_cm: None,
            span_below_cm: Some(20.0),
            span_above_cm: None,
            ..Until::default()
        };
        let condition = |until: &Until, s: Option<&KnotSpan>| until.knot_condition(s, 40.0);
        assert!(!condition(&until, Some(&span(10.0, 35.0))));
        assert!(condition(&until, Some(&span(2.5, 35.0))), "knot start near the head");
        assert!(condition(&until, Some(&span(10.0, 29.5))), "span tight enough");
        assert!(!condition(&until, None), "without contacts only the duration counts");
        let loosen = Until { span_above_cm: Some(27.0), span_below_cm: None, ..until };
        assert!(condition(&loosen, Some(&span(10.0, 37.0))));
        assert!(!condition(&loosen, Some(&span(10.0, 29.5))));
    }

    #[test]
    fn the_core_condition_looks_at_the_core_of_the_latest_recorded_frame() {
        let until = Until { seconds: 5.0, core_start_below_l: Some(0.04), ..Until::default() };
        let at = |core_start_l| Observation { core_start_l, ..seen(None) };
        let mut since = None;
        assert!(!until.over(1.0, 1.0, &at(Some(0.05)), &mut since), "still 0.05 L away");
        assert!(!until.over(1.1, 1.1, &at(None), &mut since), "an unknotted frame");
        assert!(until.over(1.2, 1.2, &at(Some(0.04)), &mut since), "within 0.04 L");

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
        let tie = TiePhase::new(TieKnot::Trefoil(crate::tie::Handedness::Right), 0.31);
        let mut controller = PhasedController::new(None, vec![Phase::Tie(tie), Phase::Hold(1.0)]);
        let unfinished = controller.unfinished_phase();
        assert_eq!(unfinished.as_deref(), Some("tie (3_1 not tied, attempt 1 of 2)"));
        controller.advance(10.0);
        assert_eq!(controller.unfinished_phase().as_deref(), Some("hold"));
        controller.advance(11.0);
        assert_eq!(controller.unfinished_phase(), None, "every phase over");
    }

    #[test]
    fn loosened_and_tightened_look_at_the_cores_length_in_diameters() {
        let loosen = Until { seconds: 5.0, core_length_above_d: Some(18.0), ..Until::default() };
        let tighten = Until { seconds: 5.0, core_length_below_d: Some(13.0), ..Until::default() };
        let at = |core_length_d| Observation { core_length_d, ..seen(None) };
        let over = |until: &Until, d| until.over(1.0, 1.0, &at(d), &mut None);
        assert!(!over(&loosen, Some(17.9)) && over(&loosen, Some(18.0)));
        assert!(!over(&tighten, Some(13.1)) && over(&tighten, Some(13.0)));
        assert!(!over(&loosen, None) && !over(&tighten, None), "an unknotted frame");

        // Relative to the core when the phase started: 14 D → loosened at 18.2 D (+30 %),
        // tightened at 10.5 D (−25 %).
        let grow = Until { seconds: 5.0, core_growth_above: Some(0.3), ..Until::default() };
        let shrink = Until { seconds: 5.0, core_shrink_above: Some(0.25), ..Until::default() };
        let from_14 = |core_length_d| Observation {
            core_length_d,
            core_length_d_at_start: Some(14.0),
            ..seen(None)
        };
        let over = |until: &Until, d| until.over(1.0, 1.0, &from_14(d), &mut None);
        assert!(!over(&grow, Some(18.1)) && over(&grow, Some(18.2)));
        assert!(!over(&shrink, Some(10.6)) && over(&shrink, Some(10.5)));
        let unknown_start = Observation { core_length_d: Some(30.0), ..seen(None) };
        assert!(!grow.over(1.0, 1.0, &unknown_start, &mut None), "no core when the phase began");
    }

    #[test]
    fn body_relative_conditions_scale_with_the_body_length() {
        let until = Until { seconds: 5.0, knot_start_below_l: Some(0.05), ..Until::default() };
        let near = span(2.5, 20.0);
        assert!(until.knot_condition(Some(&near), 60.0), "2.5 cm ≤ 0.05 · 60 cm");
        assert!(!until.knot_condition(Some(&near), 40.0), "2.5 cm > 0.05 · 40 cm");
        let tight = Until { seconds: 5.0, span_below_l: Some(0.5), ..Until::default() };
        assert!(tight.knot_condition(Some(&span(10.0, 29.0)), 40.0));
        assert!(!tight.knot_condition(Some(&span(10.0, 31.0)), 40.0));
    }

    #[test]
    fn a_knot_condition_ends_the_phase_only_after_holding_for_hold_s() {
        let until = Until {
            seconds: 5.0,
            hold_s: 0.3,
            knot_start_below_cm: None,
            knot_start_above_cm: None,
            span_below_cm: Some(20.0),
            span_above_cm: None,
            ..Until::default()
        };
        let (tight, loose) = (span(10.0, 29.5), span(10.0, 35.0));
        let mut since = None;
        assert!(!until.over(1.0, 1.0, &seen(Some(&tight)), &mut since), "a single dip");
        assert_eq!(since, Some(1.0));
        assert!(!until.over(1.1, 1.1, &seen(Some(&loose)), &mut since), "the flicker is over");
        assert_eq!(since, None);
        for t in [1.2, 1.3, 1.4] {
            assert!(!until.over(t, t, &seen(Some(&tight)), &mut since), "held only since 1.2 s");
        }
        assert!(until.over(1.5, 1.5, &seen(Some(&tight)), &mut since), "held for 0.3 s");
        assert!(until.over(5.0, 5.0, &seen(None), &mut None), "the duration ends it regardless");
    }
}
