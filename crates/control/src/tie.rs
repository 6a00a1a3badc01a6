//! Tying a knot by control, from the body's current state (the thesis' future work: "tie the
//! initial knot by using control signals"; Haney's rules, thesis §3.3.1 and §5.1).
//!
//! A [`TiePhase`] plans crossover → wrap → insertion in body-relative terms — the crossover
//! at a fraction `at` of the body length L, the sweep in fractions of L, every offset in
//! local radii — and executes it with the PD tail pull of the forming script, each waypoint
//! resolved from the body's shape when the move toward it starts (the plan, as named steps:
//! [`TiePlan`](crate::TiePlan) in `tie_plan.rs`). The knot is then checked
//! by the knot analysis of the controller's observations (type, agreement and handedness,
//! from the knotted core's writhe): tied and held for `hold_s`, the phase ends; not tied `settle_s`
//! after the plan, the plan is tried again from the current shape, up to `attempts` times,
//! and then the phase fails (the run ends with its own status, never a hang).
//!
//! Each crossing is checked as it is made ([`CrossingCheck`]): once the plan step carrying
//! the check has ended (the step after the move that makes the crossing), the tail's crossings seen from above ([`crossings_of_tail`](crate::crossings_of_tail), from the crossover on)
//! must begin with the over/under sequence the plan makes. A crossing lost or made the wrong
//! way (a loop that slipped open, a tail that went round instead of through) is kept
//! ([`CrossingMiss`]) for the run's failure message and ends the checks of that attempt;
//! the attempt itself still ends on the knot analysis, which stays the judge (abandoning at
//! once lost a figure-eight that ties when left to go on: `docs/physics.md`).
//!
//! The plan leaves the knot loose (the tail is not pulled tight): tightening is thigmotaxis'
//! job. The trefoil (either handedness) and the figure-eight are built in; any other knot is
//! a plan file ([`TieKnot::Planned`], docs/knot-plans.md).

use std::fmt;
use std::path::PathBuf;
use std::sync::Arc;

use hagfish_tree::Body;
use serde::{Deserialize, Serialize};

use crate::crossings::Layer;
use crate::knot_plan::{FIGURE_EIGHT, KnotPlan, OVERHAND};
use crate::tail_pd::TailGains;
use crate::tube_length::fraction_leaving;

/// Which way a chiral knot turns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Handedness {
    /// Positive crossings, positive writhe.
    Right,
    /// The mirror image.
    Left,
}

impl Handedness {
    /// The other one (the mirror image's).
    pub fn mirrored(self) -> Self {
        match self {
            Handedness::Right => Handedness::Left,
            Handedness::Left => Handedness::Right,
        }
    }
}

/// A knot the tie controller plans: built in, or planned by a file.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum TieKnot {
    /// The overhand knot, 3₁, of the given handedness (`data/knots/overhand.ron`).
    Trefoil(Handedness),
    /// The figure-eight knot, 4₁, achiral (`data/knots/figure_eight.ron`).
    FigureEight,
    /// The knot of a plan file ([`KnotPlan`], docs/knot-plans.md).
    Planned(PlannedKnot),
}

/// A knot planned by a file: `Planned((file: "../knots/miller_institute.ron", mirror: false))`
/// in a scenario.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlannedKnot {
    /// The plan file, relative to the scenario file's directory.
    pub file: PathBuf,
    /// Tie the mirror image: every height of the plan negated, every checked crossing and
    /// the handedness flipped.
    #[serde(default)]
    pub mirror: bool,
    /// The plan read from `file`; `None` until the scenario is loaded (an empty plan then).
    #[serde(skip)]
    pub plan: Option<Arc<KnotPlan>>,
}

impl PartialEq for PlannedKnot {
    /// The same file, mirrored the same way.
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file && self.mirror == other.mirror
    }
}

impl Eq for PlannedKnot {}

impl TieKnot {
    /// Its Rolfsen name (a planned knot's from its plan; "?" before the plan is read).
    pub fn name(&self) -> &str {
        match self {
            TieKnot::Trefoil(_) => "3_1",
            TieKnot::FigureEight => "4_1",
            TieKnot::Planned(planned) => planned.plan.as_ref().map_or("?", |p| p.knot.as_str()),
        }
    }

    /// Whether the plan is tied as its mirror image: the left-handed trefoil, a planned
    /// knot with `mirror`.
    pub fn mirrored(&self) -> bool {
        match self {
            TieKnot::Trefoil(handedness) => *handedness == Handedness::Left,
            TieKnot::FigureEight => false,
            TieKnot::Planned(planned) => planned.mirror,
        }
    }

    /// The handedness the tie must show, if it checks one.
    pub fn handedness(&self) -> Option<Handedness> {
        match self {
            TieKnot::Trefoil(handedness) => Some(*handedness),
            TieKnot::FigureEight => None,
            TieKnot::Planned(planned) => {
                let written = planned.plan.as_ref().and_then(|p| p.handedness);
                written.map(|h| if planned.mirror { h.mirrored() } else { h })
            }
        }
    }

    /// The plan, as written (before mirroring): a built-in knot's parsed from its file's
    /// text, a planned knot's as read at load. `None` for a planned knot not yet read (or a
    /// built-in text that does not parse, which a test rules out).
    pub fn plan(&self) -> Option<Arc<KnotPlan>> {
        let builtin = |text| KnotPlan::parse(text).ok().map(Arc::new);
        match self {
            TieKnot::Trefoil(_) => builtin(OVERHAND),
            TieKnot::FigureEight => builtin(FIGURE_EIGHT),
            TieKnot::Planned(planned) => planned.plan.clone(),
        }
    }

    /// Whether a knot analysis of the body (its Rolfsen name, agreement over closure
    /// directions and the core's handedness if known) shows this knot: the type with
    /// agreement ≥ [`MIN_AGREEMENT`], and where the tie checks one, the right handedness.
    pub fn is_shown_by(&self, name: &str, agreement: f64, right_handed: Option<bool>) -> bool {
        shows(self.name(), self.handedness(), name, agreement, right_handed)
    }
}

/// Whether a knot analysis (a Rolfsen name, agreement over closure directions, the core's
/// handedness if known) shows the knot `knot` of `handedness`: that type with agreement ≥
/// [`MIN_AGREEMENT`] and, where a handedness is asked, that one.
pub fn shows(
    knot: &str,
    handedness: Option<Handedness>,
    name: &str,
    agreement: f64,
    right_handed: Option<bool>,
) -> bool {
    let chirality = match handedness {
        Some(Handedness::Right) => right_handed == Some(true),
        Some(Handedness::Left) => right_handed == Some(false),
        None => true,
    };
    name == knot && agreement >= MIN_AGREEMENT && chirality
}

/// The agreement over closure directions a tied knot must reach.
pub const MIN_AGREEMENT: f64 = 0.9;

/// A check of the crossings made so far, run once the plan step that carries it has ended
/// ([`PlanStep::check`](crate::PlanStep::check)): the tail's crossings seen from above, from
/// the crossover on, must begin with `expected` (mirrored already for a mirror image).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CrossingCheck {
    /// What the check is of, for messages ("the crossover").
    pub name: String,
    /// How the crossings begin, walking from the crossover to the tail.
    pub expected: Vec<Layer>,
}

impl CrossingCheck {
    /// Whether the crossings `found` begin as this check expects.
    pub fn is_met_by(&self, found: &[Layer]) -> bool {
        found.starts_with(&self.expected)
    }
}

/// A crossing check that failed: in which attempt, which check, and the crossings found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CrossingMiss {
    /// The attempt it was found in (1-based).
    pub attempt: u32,
    /// Index of the check in the plan's checks.
    pub check: u32,
    /// The crossings found.
    pub found: LayerCode,
}

/// An over/under sequence of up to 32 crossings as plain data (bit k set: crossing k over),
/// so that a [`CrossingMiss`] can live in a checkpoint.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct LayerCode {
    /// Bit k is set when crossing k is [`Layer::Over`].
    pub over_bits: u32,
    /// How many crossings (at most 32 are kept).
    pub len: u32,
}

impl LayerCode {
    /// The first 32 layers of `layers`.
    pub fn of(layers: &[Layer]) -> Self {
        let kept = &layers[..layers.len().min(32)];
        let over_bits = kept
            .iter()
            .enumerate()
            .filter(|(_, l)| **l == Layer::Over)
            .fold(0, |bits, (k, _)| bits | 1 << k);
        Self { over_bits, len: kept.len() as u32 }
    }
}

impl fmt::Display for LayerCode {
    /// "over, under, over", or "none".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.len == 0 {
            return f.write_str("none");
        }
        for k in 0..self.len {
            let layer = if self.over_bits >> k & 1 == 1 { "over" } else { "under" };
            write!(f, "{}{layer}", if k > 0 { ", " } else { "" })?;
        }
        Ok(())
    }
}

/// A tie phase: which knot, where, and how patiently.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TiePhase {
    /// The knot to tie.
    pub knot: TieKnot,
    /// Where the crossover is made: a fraction of the body length from the head (the knot
    /// forms tail-ward of it), in (0, 1).
    pub at: f64,
    /// The least body to leave tail-ward of the crossover, in local diameters (∫ ds / 2r), if
    /// any (D17): on a body where `at` would leave less (shorter or thicker than the one the plan
    /// was made on), the crossover moves head-ward until it leaves this much
    /// ([`TiePhase::on_body`]). The plan's loop and tail are fractions of the body tail-ward
    /// of the crossover, so this keeps the knot's size and the tail beyond it in diameters.
    #[serde(default)]
    pub min_tail_d: Option<f64>,
    /// Gains of the tail pull.
    #[serde(default)]
    pub gains: TailGains,
    /// Speed of the tail's target (cm/s; default 5).
    #[serde(default = "default_speed")]
    pub speed_cm_s: f64,
    /// Speed of the tail's target on the attempts after the first (cm/s; default
    /// `speed_cm_s`): soft and fine chains tie with a slower tail, stiff ones with a faster
    /// one (docs/physics.md, the figure-eight).
    #[serde(default)]
    pub retry_speed_cm_s: Option<f64>,
    /// Plans tried before the phase fails (default 2).
    #[serde(default = "default_attempts")]
    pub attempts: u32,
    /// How long the knot must be shown without interruption before the phase ends (s,
    /// default 0.5).
    #[serde(default = "default_hold")]
    pub hold_s: f64,
    /// How long after the plan's last step the knot may take to show before the attempt
    /// counts as failed (s, default 2).
    #[serde(default = "default_settle")]
    pub settle_s: f64,
    /// Hold the crossings the tie has made (dyn, the largest force of each hold), if set:
    /// once a crossing check passes, each crossing it checked is held while the tail makes
    /// the next ones — a soft row on the self contact at that crossing,
    /// `t_bᵀ(P(u_b) − P(u_a)) q̇ ≥ 0`, so that the tail-ward strand does not slide back
    /// through it ([`HeldCrossing`]). Default `None`: no hold.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hold_crossings_dyn: Option<f64>,
}

/// A crossing the tie holds: where it lies on its two strands (spline parameters, body index
/// plus fraction), followed from step to step as the self contact there moves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeldCrossing {
    /// On the tail-ward strand (the contact's posterior point, `u_b`).
    pub tail_u: f64,
    /// On the head-ward strand (the contact's anterior point, `u_a`).
    pub other_u: f64,
}

/// The most crossings a tie holds at once (the first ones its checks pass).
pub const MAX_HELD_CROSSINGS: usize = 8;

/// How far (in bodies, on each strand) a held crossing's contact may have moved since the
/// step before and still be taken for it.
pub const HOLD_REACH_BODIES: f64 = 3.0;

fn default_speed() -> f64 {
    5.0
}

fn default_attempts() -> u32 {
    2
}

fn default_hold() -> f64 {
    0.5
}

fn default_settle() -> f64 {
    2.0
}

impl TiePhase {
    /// A tie phase for `knot` with the crossover at `at` (fraction of L) and every other
    /// setting at its default.
    pub fn new(knot: TieKnot, at: f64) -> Self {
        Self {
            knot,
            at,
            min_tail_d: None,
            gains: TailGains::default(),
            speed_cm_s: default_speed(),
            retry_speed_cm_s: None,
            attempts: default_attempts(),
            hold_s: default_hold(),
            settle_s: default_settle(),
            hold_crossings_dyn: None,
        }
    }

    /// This phase on a body of `bodies` (head to tail): the crossover at `at`, or head-ward of
    /// it where `at` would leave less than `min_tail_d` local diameters of body tail-ward of
    /// it ([`fraction_leaving`]; at the head if the whole body is shorter).
    pub fn on_body(&self, bodies: &[Body]) -> TiePhase {
        let at = match self.min_tail_d {
            Some(diameters) => self.at.min(fraction_leaving(bodies, diameters)),
            None => self.at,
        };
        TiePhase { at, ..self.clone() }
    }
}

/// Progress of a tie phase: the controller state a checkpoint must keep (with the forming
/// script's progress).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TieProgress {
    /// Attempts started (1 during the first).
    pub attempt: u32,
    /// When the current attempt's plan ended (s), if it has.
    pub plan_done_at: Option<f64>,
    /// Since when the knot has been shown without interruption (s), if it is.
    pub shown_since: Option<f64>,
    /// True once the last attempt failed.
    pub failed: bool,
    /// Crossing checks done in the current attempt: those passed, or all of them once one
    /// failed.
    #[serde(default)]
    pub checks_done: u32,
    /// The latest crossing check that failed, in any attempt.
    #[serde(default)]
    pub last_miss: Option<CrossingMiss>,
    /// The crossings held in the current attempt (`hold_crossings_dyn`), in the order made.
    #[serde(default, skip_serializing_if = "holds_none")]
    pub held: [Option<HeldCrossing>; MAX_HELD_CROSSINGS],
}

/// Whether no crossing is held (then `held` is left out of a checkpoint).
fn holds_none(held: &[Option<HeldCrossing>; MAX_HELD_CROSSINGS]) -> bool {
    held.iter().all(Option::is_none)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crossings::Crossing;
    use crate::phases::{KnotObservation, Phase, PhasedController};

    fn phase(handedness: Handedness) -> TiePhase {
        TiePhase::new(TieKnot::Trefoil(handedness), 0.31)
    }

    /// A uniform tube of 40 bodies 0.5 cm long and `radius` cm in radius: 10 / radius diameters.
    fn tube(radius: f64) -> Vec<Body> {
        vec![crate::tube_length::cylinder(0.5, radius); 40]
    }

    #[test]
    fn the_crossover_moves_head_ward_only_where_the_tail_would_be_too_short() {
        let tie = TiePhase { min_tail_d: Some(25.0), ..phase(Handedness::Right) };
        // 0.69 of 40 D = 27.6 D tail-ward of 0.31 L: enough, the crossover stays.
        assert_eq!(tie.on_body(&tube(0.25)).at, 0.31);
        // 1.25 × as thick: 32 D in all, 22.1 D tail-ward of 0.31 L; 25 D from 1 − 25/32.
        let at = tie.on_body(&tube(0.3125)).at;
        assert!((at - (1.0 - 25.0 / 32.0)).abs() < 1e-12, "{at}");
        assert_eq!(tie.on_body(&tube(0.5)).at, 0.0, "a body of 20 D: at the head");
        let plain = phase(Handedness::Right);
        assert_eq!(plain.on_body(&tube(0.5)), plain, "no min_tail_d: as given");
    }

    #[test]
    fn a_knot_is_shown_only_with_its_type_agreement_and_handedness() {
        let right = TieKnot::Trefoil(Handedness::Right);
        assert!(right.is_shown_by("3_1", 0.95, Some(true)));
        assert!(!right.is_shown_by("3_1", 0.95, Some(false)), "the mirror image");
        assert!(!right.is_shown_by("3_1", 0.95, None), "handedness unknown");
        assert!(!right.is_shown_by("3_1", 0.85, Some(true)), "agreement below 0.9");
        assert!(!right.is_shown_by("0_1", 1.0, Some(true)));
        let eight = TieKnot::FigureEight;
        assert!(eight.is_shown_by("4_1", 0.95, None), "achiral: no handedness asked");
        assert!(!eight.is_shown_by("3_1", 0.95, Some(true)));
    }

    #[test]
    fn a_tie_ends_when_shown_for_hold_s_and_fails_after_its_attempts() {
        let tie = |attempts| {
            PhasedController::new(
                None,
                vec![Phase::Tie(TiePhase { attempts, ..phase(Handedness::Right) })],
            )
        };
        let seen = |name, agreement, right_handed| {
            let (core_start_l, core_length_d) = (Some(0.4), Some(14.0));
            Some(KnotObservation { name, agreement, right_handed, core_start_l, core_length_d })
        };
        let shown = seen("3_1", 0.95, Some(true));
        let mut controller = tie(2);
        controller.observe_knot(10.0, shown);
        assert_eq!(controller.state().tie.shown_since, Some(10.0));
        controller.observe_knot(10.1, seen("0_1", 1.0, None));
        assert_eq!(controller.state().tie.shown_since, None, "an interruption restarts the hold");

        // Not shown 2 s after the plan ended: the second attempt starts, then the phase fails.
        let mut controller = tie(2);
        controller.tie.plan_done_at = Some(20.0);
        controller.observe_knot(21.9, None);
        assert_eq!(controller.state().tie.attempt, 1, "still settling");
        controller.observe_knot(22.0, None);
        assert_eq!(controller.state().tie.attempt, 2);
        assert_eq!(controller.state().tie.plan_done_at, None, "the plan starts again");
        assert!(controller.tie_failure().is_none());
        controller.tie.plan_done_at = Some(40.0);
        controller.observe_knot(42.0, None);
        let failure = controller.tie_failure().expect("failed");
        assert_eq!((failure.knot.as_str(), failure.attempts), ("3_1", 2));
    }

    /// Crossings of the given layers, the k-th at body 50 + k of the tail-ward strand and
    /// 10 + k of the other.
    fn crossings(layers: &[Layer]) -> Vec<Crossing> {
        let at = |k: usize| (50.0 + k as f64, 10.0 + k as f64);
        let crossing =
            |(k, &layer): (usize, &Layer)| Crossing { tail_u: at(k).0, other_u: at(k).1, layer };
        layers.iter().enumerate().map(crossing).collect()
    }

    #[test]
    fn a_passed_check_holds_the_crossings_it_checked_when_the_phase_holds() {
        use Layer::{Over, Under};
        let holding = |hold: Option<f64>| {
            let phase =
                TiePhase { hold_crossings_dyn: hold, ..TiePhase::new(TieKnot::FigureEight, 0.31) };
            let mut controller = PhasedController::new(None, vec![Phase::Tie(phase)]);
            at_step(&mut controller, 7);
            controller.observe_crossings(&crossings(&[Over, Under]));
            controller.state().tie.held
        };
        let held = holding(Some(500.0));
        assert_eq!(held[0], Some(HeldCrossing { tail_u: 50.0, other_u: 10.0 }), "{held:?}");
        assert!(
            held[1..].iter().all(Option::is_none),
            "the crossover's check covers one: {held:?}"
        );
        assert!(holding(None).iter().all(Option::is_none), "no hold asked");
    }

    fn tie_controller(knot: TieKnot, attempts: u32) -> PhasedController {
        let phase = TiePhase { attempts, ..TiePhase::new(knot, 0.31) };
        PhasedController::new(None, vec![Phase::Tie(phase)])
    }

    fn at_step(controller: &mut PhasedController, step: usize) {
        controller.forming.as_mut().expect("a plan").progress.step = step;
    }

    #[test]
    fn a_crossing_made_the_wrong_way_is_kept_for_the_failure_message() {
        use Layer::{Over, Under};
        let mut controller = tie_controller(TieKnot::Trefoil(Handedness::Right), 2);
        at_step(&mut controller, 6);
        controller.observe_crossings(&crossings(&[Under]));
        assert_eq!(controller.state().tie.last_miss, None, "not due before its step has ended");
        at_step(&mut controller, 7);
        controller.observe_crossings(&crossings(&[Over, Under]));
        assert_eq!(controller.state().tie.checks_done, 1, "a sequence that begins right");
        at_step(&mut controller, 10);
        controller.observe_crossings(&crossings(&[Under, Over]));
        let tie = controller.state().tie;
        assert_eq!((tie.attempt, tie.checks_done), (1, 2), "kept; no more checks this attempt");
        let miss = tie.last_miss.expect("kept");
        assert_eq!((miss.attempt, miss.check), (1, 1));
        assert_eq!(miss.found, LayerCode::of(&[Under, Over]));
        assert_eq!(controller.forming.as_ref().map(|f| f.progress().step), Some(10), "no restart");

        // The attempts end on the knot analysis, as without checks; the failure says where.
        controller.tie.plan_done_at = Some(20.0);
        controller.observe_knot(22.0, None);
        assert_eq!(controller.state().tie.attempt, 2);
        assert_eq!(controller.state().tie.last_miss, Some(miss), "kept across attempts");
        at_step(&mut controller, 7);
        controller.observe_crossings(&crossings(&[]));
        controller.tie.plan_done_at = Some(40.0);
        controller.observe_knot(42.0, None);
        let failure = controller.tie_failure().expect("failed");
        assert_eq!(failure.attempts, 2);
        assert_eq!(
            failure.to_string(),
            "3_1 after 2 attempts (attempt 2: after the crossover the tail's crossings seen \
             from above were none; the plan makes over)"
        );
    }

    #[test]
    fn the_mirror_image_checks_mirrored_crossings_and_a_shown_knot_overrides_a_check() {
        use Layer::{Over, Under};
        let mut left = tie_controller(TieKnot::Trefoil(Handedness::Left), 2);
        at_step(&mut left, 10);
        left.observe_crossings(&crossings(&[Under, Over, Over]));
        assert_eq!(left.state().tie.checks_done, 2);
        assert_eq!(left.state().tie.attempt, 1);

        let mut eight = tie_controller(TieKnot::FigureEight, 1);
        let shown = KnotObservation {
            name: "4_1",
            agreement: 1.0,
            right_handed: None,
            core_start_l: Some(0.3),
            core_length_d: Some(17.0),
        };
        eight.observe_knot(12.0, Some(shown));
        at_step(&mut eight, 13);
        eight.observe_crossings(&crossings(&[Under]));
        assert!(eight.tie_failure().is_none(), "the knot analysis is the judge");
        assert_eq!(eight.state().tie.checks_done, 4);
    }

    #[test]
    fn a_layer_code_keeps_the_sequence_for_messages() {
        use Layer::{Over, Under};
        assert_eq!(LayerCode::of(&[Over, Under, Over]).to_string(), "over, under, over");
        assert_eq!(LayerCode::of(&[]).to_string(), "none");
        assert_eq!(LayerCode::of(&[Under; 40]).len, 32, "at most 32 kept");
    }
}
