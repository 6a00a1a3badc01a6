//! The plan of one tie attempt as named steps ([`TiePlan`]): crossover → wrap → insertion in
//! body-relative terms, each step a move or hold of the forming script, and each crossing
//! check ([`CrossingCheck`]) carried by the step after whose end it runs, so that reordering
//! the plan moves a check with its step. It is a knot's plan file ([`crate::KnotPlan`]) made
//! concrete for one phase and attempt: the crossover's place, the speed, the mirror image.

use crate::forming::{FormingScript, ScriptStep};
use crate::tail_pd::TailGains;
use crate::tie::{CrossingCheck, TiePhase};

/// One named step of a tie plan: a move or hold of the forming script, and the crossing check
/// that runs once it has ended, if any.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanStep {
    /// What the step does ("cross over the body"): how the plan reads, and how a test finds it.
    pub name: String,
    /// The move or hold.
    pub step: ScriptStep,
    /// The crossing check that runs once this step has ended. A check rides on the step after
    /// the move that makes its crossing, since the tail lags its target (read step by step on
    /// 33 ties of 11 bodies: every one that succeeded made the sequences checked here;
    /// `docs/physics.md` has the one exception seen since).
    pub check: Option<CrossingCheck>,
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
    pub fn checks(&self) -> impl Iterator<Item = (usize, &CrossingCheck)> + '_ {
        self.steps.iter().enumerate().filter_map(|(k, s)| s.check.as_ref().map(|check| (k, check)))
    }
}

impl TiePhase {
    /// The plan of attempt `attempt` (from 1): the knot's plan ([`crate::TieKnot::plan`])
    /// with the crossover at `at`, mirrored for a mirror image, moving at `retry_speed_cm_s`
    /// after the first attempt where that is set, else at `speed_cm_s`. Empty for a planned
    /// knot whose file was never read.
    pub fn plan_for(&self, attempt: u32) -> TiePlan {
        let speed = match self.retry_speed_cm_s {
            Some(retry) if attempt > 1 => retry,
            _ => self.speed_cm_s,
        };
        match self.knot.plan() {
            Some(plan) => plan.tie_plan(self.at, speed, self.knot.mirrored()),
            None => TiePlan { steps: Vec::new() },
        }
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
    use crate::crossings::Layer;
    use crate::forming::Waypoint;
    use crate::tie::{Handedness, TieKnot};

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
            let plan = TiePhase::new(knot.clone(), 0.31).plan_for(1);
            let checks: Vec<(usize, &CrossingCheck)> = plan.checks().collect();
            let descent = plan
                .steps
                .iter()
                .position(|s| {
                    matches!(s.step, ScriptStep::Move { to: Waypoint::FromArc { at, offset_radii }, .. }
                        if at == 0.31 && offset_radii[1] < 0.0 && offset_radii[2] < 0.0)
                })
                .expect("the crossover's move down");
            assert_eq!(checks[0].0, descent + 1, "{knot:?}: one step after the crossover");
            assert_eq!(
                checks[0].1,
                &CrossingCheck { name: "the crossover".into(), expected: vec![Layer::Over] }
            );
            assert!(checks.windows(2).all(|w| w[0].0 < w[1].0));
            assert!(checks.windows(2).all(|w| w[1].1.expected.starts_with(&w[0].1.expected)));
            let &(last, _) = checks.last().expect("checks");
            assert_eq!(last, plan.steps.len() - 1, "{knot:?}: the last after the plan");
            assert!(matches!(plan.steps[last].step, ScriptStep::Hold(_)));
            let names: Vec<&str> = checks.iter().map(|(_, c)| c.name.as_str()).collect();
            let expected = match knot {
                TieKnot::Trefoil(_) => vec!["the crossover", "the insertion"],
                _ => vec!["the crossover", "the wrap", "the threading", "the insertion"],
            };
            assert_eq!(names, expected, "{knot:?}");
        }
    }

    /// A check is carried by its step: moved with the step, it runs after that same named
    /// step at its new place, and the steps it left keep none.
    #[test]
    fn a_check_moves_with_its_step_when_the_plan_is_reordered() {
        let plan = TiePhase::new(TieKnot::FigureEight, 0.31).plan_for(1);
        let carrying = |plan: &TiePlan| -> Vec<(String, String, usize)> {
            let name = |k: usize| plan.steps[k].name.clone();
            plan.checks().map(|(k, check)| (check.name.clone(), name(k), k)).collect()
        };
        let before = carrying(&plan);
        let position = |plan: &TiePlan, name: &str| plan.steps.iter().position(|s| s.name == name);
        let wrap_step = position(&plan, "up beside the strand").expect("the wrap's last move");
        let named = |check: &str, step: &str, at| (check.to_string(), step.to_string(), at);
        assert!(before.contains(&named("the wrap", "up beside the strand", wrap_step)));

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
        assert_eq!(after[0], named("the crossover", "under the strand", 0));
        assert_eq!(after[1], named("the wrap", "up beside the strand", wrap_step + 1));
        let script = reordered.script(TailGains::default());
        assert_eq!(script.steps[wrap_step + 1], plan.steps[wrap_step].step, "the move went too");
    }
}
