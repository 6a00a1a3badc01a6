//! The plan of one tie attempt as named steps ([`TiePlan`]): crossover → wrap → insertion in
//! body-relative terms, each step a move or hold of the forming script, and each crossing
//! check ([`CrossingCheck`]) carried by the step after whose end it runs, so that reordering
//! the plan moves a check with its step.
//!
//! Units: the sweep in body lengths L, as fractions of the body's remaining length R = 1 − a
//! tail-ward of the crossover at `a`; offsets at the crossover and the wrap in the local
//! radius r of the body there; offsets at the loop in mean body radii; holds in seconds.

use crate::crossings::Layer::{Over, Under};
use crate::forming::{FormingScript, ScriptStep, Waypoint};
use crate::tail_pd::TailGains;
use crate::tie::{CrossingCheck, Handedness, TieKnot, TiePhase};

/// The sweep's far point: (along, aside) as fractions of R, the target at
/// (a + along·R, aside·R, 0)·L; it swings the tail wide of the body.
const SWEEP_OUT: [f64; 2] = [0.63, 0.6];

/// Where the sweep comes back to, in the same terms, so the body lies as a "C".
const SWEEP_BACK: [f64; 2] = [0.17, 0.45];

/// How long the target is held still for the loop to settle before the crossover, and after
/// the plan (s).
const SETTLE_S: f64 = 1.0;

/// The side offset (local radii) at which the tail rises beside the body before crossing it.
const NEAR_SIDE_R: f64 = 3.5;

/// The side offset (local radii) on the far side of the body after crossing it; the
/// figure-eight's wrap passes the loop's strand at the same distance on either side.
const FAR_SIDE_R: f64 = 4.7;

/// The height (local radii) above the body when crossing over it and below it afterwards;
/// the depth below the loop's strand in the figure-eight's wrap.
const CLEARANCE_R: f64 = 3.0;

/// The height (local radii) above the loop's strand at the end of the figure-eight's wrap.
const OVER_STRAND_R: f64 = 3.5;

/// The depth (mean radii) below the loop's centroid from which the trefoil's tail goes up
/// through the loop.
const UNDER_LOOP_R: f64 = 3.0;

/// The height (mean radii) off the loop's centroid on the far side of the loop: above it
/// after the trefoil's tail has gone up through, above and then below it for the
/// figure-eight's tail going down through.
const THROUGH_LOOP_R: f64 = 3.5;

/// How much further (mean radii) the tail goes on through the loop: a tail end left just
/// through the loop slips back out (measured on ES103: the knot showed for one frame).
const BEYOND_R: f64 = 6.0;

/// How far tail-ward of the crossover (fraction of L) the figure-eight's tail wraps the loop.
/// Wrapping the standing part head-ward of the crossover instead ties a trefoil (measured at
/// `a − 0.04`, `a − 0.08`).
const FIGURE_EIGHT_WRAP: f64 = 0.04;

/// Over the body at the crossover; checked after the first move past it.
const CROSSOVER: CrossingCheck = CrossingCheck { name: "the crossover", expected: &[Over] };

/// The trefoil's insertion: under the loop's strand and up through the loop.
const TREFOIL_INSERTION: CrossingCheck =
    CrossingCheck { name: "the insertion", expected: &[Over, Under] };

/// The figure-eight's wrap: under the loop's strand.
const WRAP: CrossingCheck = CrossingCheck { name: "the wrap", expected: &[Over, Under] };

/// The figure-eight's threading: over the loop's strand on the way to above the loop.
const THREADING: CrossingCheck =
    CrossingCheck { name: "the threading", expected: &[Over, Under, Over] };

/// The figure-eight's insertion: still so once down through the loop and after the plan.
const FIGURE_EIGHT_INSERTION: CrossingCheck =
    CrossingCheck { name: "the insertion", expected: &[Over, Under, Over] };

/// One named step of a tie plan: a move or hold of the forming script, and the crossing check
/// that runs once it has ended, if any.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanStep {
    /// What the step does ("cross over the body"): how the plan reads, and how a test finds it.
    pub name: &'static str,
    /// The move or hold.
    pub step: ScriptStep,
    /// The crossing check that runs once this step has ended. A check rides on the step after
    /// the move that makes its crossing, since the tail lags its target (read step by step on
    /// 33 ties of 11 bodies: every one that succeeded made the sequences checked here;
    /// `docs/physics.md` has the one exception seen since).
    pub check: Option<CrossingCheck>,
}

impl PlanStep {
    /// This step carrying `check`.
    fn checked(self, check: CrossingCheck) -> Self {
        Self { check: Some(check), ..self }
    }
}

/// The plan of one tie attempt: named steps, in order.
#[derive(Clone, Debug, PartialEq)]
pub struct TiePlan {
    /// The steps, in order.
    pub steps: Vec<PlanStep>,
}

impl TiePlan {
    /// The forming script that executes the plan with the tail pull `gains`: its moves and
    /// holds, in order.
    pub fn script(&self, gains: TailGains) -> FormingScript {
        FormingScript { gains, steps: self.steps.iter().map(|s| s.step).collect() }
    }

    /// The crossing checks in order, each with the index of the step after whose end it runs
    /// (the check is due once the forming script's step index is past it).
    pub fn checks(&self) -> impl Iterator<Item = (usize, CrossingCheck)> + '_ {
        self.steps.iter().enumerate().filter_map(|(k, s)| s.check.map(|check| (k, check)))
    }
}

impl TiePhase {
    /// The plan of attempt `attempt` (from 1), moving at `retry_speed_cm_s` after the first
    /// attempt where that is set, else at `speed_cm_s`. With the crossover at `a = at` and R =
    /// 1 − a (the constants of `tie_plan.rs` name every coefficient):
    /// - the loop: sweep the tail wide, to (a + 0.63R, 0.6R, 0)·L then back to
    ///   (a + 0.17R, 0.45R, 0)·L so the body lies as a "C", hold 1 s; cross over the body at
    ///   `at` (3.5 r to one side and 3 r up, over to 4.7 r on the other side, down to 3 r below);
    /// - trefoil: go under the loop's centroid (3 r below), up through it (3.5 r above) and 6 r
    ///   further. Crossing over first gives the right-handed trefoil (writhe ≈ +2.3 on ES103);
    ///   the left-handed one is the mirror image in z (under first);
    /// - figure-eight: wrap the loop's own strand tail-ward of the crossover, at
    ///   `a + 0.04` (under it to 4.7 r on the first side, up to 3.5 r above), then thread the
    ///   loop from above (3.5 r above its centroid, 3.5 r below, 6 r further);
    /// - then hold 1 s.
    pub fn plan_for(&self, attempt: u32) -> TiePlan {
        let speed = match self.retry_speed_cm_s {
            Some(retry) if attempt > 1 => retry,
            _ => self.speed_cm_s,
        };
        let z = match self.knot {
            TieKnot::Trefoil(Handedness::Left) => -1.0,
            TieKnot::Trefoil(Handedness::Right) | TieKnot::FigureEight => 1.0,
        };
        let (a, rest) = (self.at, 1.0 - self.at);
        let step = |name, to| PlanStep { name, step: ScriptStep::Move { to, speed }, check: None };
        let hold = |name| PlanStep { name, step: ScriptStep::Hold(SETTLE_S), check: None };
        let sweep =
            |[along, aside]: [f64; 2]| Waypoint::BodyLengths([a + along * rest, aside * rest, 0.0]);
        let arc =
            |at: f64, y: f64, up: f64| Waypoint::FromArc { at, offset_radii: [0.0, y, z * up] };
        let centroid = |up: f64| Waypoint::FromLoopCentroidRadii([0.0, 0.0, z * up]);
        let further = |up: f64| Waypoint::FromTargetRadii([0.0, 0.0, z * up]);
        let mut steps = vec![
            step("sweep out", sweep(SWEEP_OUT)),
            step("sweep back", sweep(SWEEP_BACK)),
            hold("let the loop settle"),
            step("rise beside the body", arc(a, NEAR_SIDE_R, CLEARANCE_R)),
            step("cross over the body", arc(a, -FAR_SIDE_R, CLEARANCE_R)),
            step("drop past the body", arc(a, -FAR_SIDE_R, -CLEARANCE_R)),
        ];
        let insertion = match self.knot {
            // Up through the loop from below.
            TieKnot::Trefoil(_) => {
                steps.extend([
                    step("under the loop", centroid(-UNDER_LOOP_R)).checked(CROSSOVER),
                    step("up through the loop", centroid(THROUGH_LOOP_R)),
                    step("on through the loop", further(BEYOND_R)),
                ]);
                TREFOIL_INSERTION
            }
            // Around the loop's strand, then down through the loop from above.
            TieKnot::FigureEight => {
                let wrap = a + FIGURE_EIGHT_WRAP;
                steps.extend([
                    step("under the strand", arc(wrap, -FAR_SIDE_R, -CLEARANCE_R))
                        .checked(CROSSOVER),
                    step("across under the strand", arc(wrap, FAR_SIDE_R, -CLEARANCE_R)),
                    step("up beside the strand", arc(wrap, FAR_SIDE_R, OVER_STRAND_R))
                        .checked(WRAP),
                    step("above the loop", centroid(THROUGH_LOOP_R)),
                    step("down through the loop", centroid(-THROUGH_LOOP_R)).checked(THREADING),
                    step("on through the loop", further(-BEYOND_R)),
                ]);
                FIGURE_EIGHT_INSERTION
            }
        };
        steps.push(hold("hold the tail through the loop").checked(insertion));
        TiePlan { steps }
    }

    /// The plan of attempt `attempt` (from 1) as a forming script ([`TiePhase::plan_for`]).
    pub fn script_for(&self, attempt: u32) -> FormingScript {
        self.plan_for(attempt).script(self.gains)
    }

    /// The plan of the first attempt as a forming script.
    pub fn script(&self) -> FormingScript {
        self.script_for(1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn phase(handedness: Handedness) -> TiePhase {
        TiePhase::new(TieKnot::Trefoil(handedness), 0.31)
    }

    #[test]
    fn attempts_after_the_first_move_at_the_retry_speed() {
        let speeds = |tie: &TiePhase, attempt| -> Vec<f64> {
            let script = tie.script_for(attempt);
            let moves = script.steps.iter().filter_map(|step| match step {
                ScriptStep::Move { speed, .. } => Some(*speed),
                ScriptStep::Hold(_) => None,
            });
            moves.collect()
        };
        let mut tie = TiePhase::new(TieKnot::FigureEight, 0.31);
        assert!(speeds(&tie, 2).iter().all(|&v| v == 5.0), "{:?}", speeds(&tie, 2));
        tie.speed_cm_s = 3.0;
        tie.retry_speed_cm_s = Some(5.0);
        assert_eq!(tie.script(), tie.script_for(1));
        assert!(speeds(&tie, 1).iter().all(|&v| v == 3.0), "{:?}", speeds(&tie, 1));
        for attempt in [2, 3] {
            assert!(speeds(&tie, attempt).iter().all(|&v| v == 5.0), "attempt {attempt}");
        }
    }

    #[test]
    fn the_left_handed_plan_is_the_right_handed_one_mirrored_in_z() {
        let (right, left) = (phase(Handedness::Right).script(), phase(Handedness::Left).script());
        assert_eq!(right.steps.len(), left.steps.len());
        let mirrored = |w: Waypoint| match w {
            Waypoint::FromArc { at, offset_radii: [x, y, z] } => {
                Waypoint::FromArc { at, offset_radii: [x, y, -z] }
            }
            Waypoint::FromLoopCentroidRadii([x, y, z]) => {
                Waypoint::FromLoopCentroidRadii([x, y, -z])
            }
            Waypoint::FromTargetRadii([x, y, z]) => Waypoint::FromTargetRadii([x, y, -z]),
            other => other,
        };
        for (r, l) in right.steps.iter().zip(&left.steps) {
            match (*r, *l) {
                (ScriptStep::Move { to: a, .. }, ScriptStep::Move { to: b, .. }) => {
                    assert_eq!(mirrored(a), b);
                }
                (a, b) => assert_eq!(a, b),
            }
        }
        // Crossing over first (positive z at the crossover) is the right-handed trefoil.
        let over = right.steps.iter().find_map(|s| match s {
            ScriptStep::Move { to: Waypoint::FromArc { offset_radii, .. }, .. } => {
                Some(offset_radii[2])
            }
            _ => None,
        });
        assert!(over.is_some_and(|z| z > 0.0));
    }

    /// Each check runs after a step of the plan, in order; the first one step after the
    /// crossover's move down past the body, the last after the plan's final hold; each
    /// expects what the one before it did and more.
    #[test]
    fn the_crossing_checks_follow_the_plan() {
        for knot in [TieKnot::Trefoil(Handedness::Right), TieKnot::FigureEight] {
            let plan = TiePhase::new(knot, 0.31).plan_for(1);
            let checks: Vec<(usize, CrossingCheck)> = plan.checks().collect();
            let descent = plan
                .steps
                .iter()
                .position(|s| {
                    matches!(s.step, ScriptStep::Move { to: Waypoint::FromArc { at, offset_radii }, .. }
                        if at == 0.31 && offset_radii[1] < 0.0 && offset_radii[2] < 0.0)
                })
                .expect("the crossover's move down");
            assert_eq!(checks[0].0, descent + 1, "{knot:?}: one step after the crossover");
            assert_eq!(checks[0].1, CROSSOVER);
            assert!(checks.windows(2).all(|w| w[0].0 < w[1].0));
            assert!(checks.windows(2).all(|w| w[1].1.expected.starts_with(w[0].1.expected)));
            let &(last, _) = checks.last().expect("checks");
            assert_eq!(last, plan.steps.len() - 1, "{knot:?}: the last after the plan");
            assert!(matches!(plan.steps[last].step, ScriptStep::Hold(_)));
            let names: Vec<&str> = checks.iter().map(|(_, c)| c.name).collect();
            let expected = match knot {
                TieKnot::Trefoil(_) => vec!["the crossover", "the insertion"],
                TieKnot::FigureEight => {
                    vec!["the crossover", "the wrap", "the threading", "the insertion"]
                }
            };
            assert_eq!(names, expected, "{knot:?}");
        }
    }

    /// A check is carried by its step: moved with the step, it runs after that same named
    /// step at its new place, and the steps it left keep none.
    #[test]
    fn a_check_moves_with_its_step_when_the_plan_is_reordered() {
        let plan = TiePhase::new(TieKnot::FigureEight, 0.31).plan_for(1);
        let carrying = |plan: &TiePlan| -> Vec<(&'static str, &'static str, usize)> {
            let name = |k: usize| plan.steps[k].name;
            plan.checks().map(|(k, check)| (check.name, name(k), k)).collect()
        };
        let before = carrying(&plan);
        let position = |plan: &TiePlan, name| plan.steps.iter().position(|s| s.name == name);
        let wrap_step = position(&plan, "up beside the strand").expect("the wrap's last move");
        assert!(before.contains(&("the wrap", "up beside the strand", wrap_step)));

        // Swap the wrap's checked move with the unchecked move after it, and move the
        // crossover's checked step to the front.
        let mut reordered = plan.clone();
        reordered.steps.swap(wrap_step, wrap_step + 1);
        let crossover = position(&reordered, "under the strand").expect("the crossover's step");
        let moved = reordered.steps.remove(crossover);
        reordered.steps.insert(0, moved);

        let after = carrying(&reordered);
        assert_eq!(after.len(), before.len());
        for ((check, step, _), (check_now, step_now, at_now)) in before.iter().zip(&after) {
            assert_eq!((check, step), (check_now, step_now), "the same check after the same step");
            assert_eq!(Some(*at_now), position(&reordered, step_now), "{check} at its new place");
        }
        assert_eq!(after[0], ("the crossover", "under the strand", 0));
        assert_eq!(after[1], ("the wrap", "up beside the strand", wrap_step + 1));
        let script = reordered.script(TailGains::default());
        assert_eq!(script.steps[wrap_step + 1], plan.steps[wrap_step].step, "the move went too");
    }
}
