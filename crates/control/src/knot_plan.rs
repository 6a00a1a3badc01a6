//! A knot's tie plan as data (docs/knot-plans.md): the named steps of crossover → wrap →
//! insertion in body-relative terms, each with the crossing check that runs after it. The
//! overhand and figure-eight plans are the files `data/knots/overhand.ron` and
//! `data/knots/figure_eight.ron`, built in; a scenario names any other plan file
//! ([`crate::TieKnot::Planned`]), so a knot is added without editing Rust.
//!
//! Units, with the crossover at a fraction `a` of the body length L and R = 1 − a:
//! - `Sweep(along, aside)`: the target at (a + along·R, aside·R, 0)·L;
//! - `Arc(past_crossover, aside_r, up_r)`: (0, aside_r, ±up_r) local radii from the centre of
//!   the body at a + past_crossover (fraction of L);
//! - `LoopCentroid(up_r)`: (0, 0, ±up_r) mean radii from the largest loop's centroid seen
//!   from above;
//! - `Beyond(up_r)`: (0, 0, ±up_r) mean radii from the previous target;
//! - `Hold(s)`: the target held still for s seconds;
//!
//! where ± is + as written and − for the mirror image.

use serde::{Deserialize, Serialize};

use crate::crossings::Layer;
use crate::forming::{ScriptStep, Waypoint};
use crate::tie::{CrossingCheck, Handedness};
use crate::tie_plan::{PlanStep, TiePlan};

/// The overhand knot's plan (right-handed as written), `data/knots/overhand.ron`.
pub const OVERHAND: &str = include_str!("../../../data/knots/overhand.ron");

/// The figure-eight knot's plan, `data/knots/figure_eight.ron`.
pub const FIGURE_EIGHT: &str = include_str!("../../../data/knots/figure_eight.ron");

/// A tie plan: the knot it ties and its steps, in order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KnotPlan {
    /// The knot's Rolfsen name (`6_2`): what the knot analysis must show for the tie to end.
    pub knot: String,
    /// The handedness (sign of the knotted core's writhe) the plan ties as written, `None`
    /// for an achiral knot or one whose handedness the tie does not check; the mirror image
    /// ties the other.
    pub handedness: Option<Handedness>,
    /// The steps, in order.
    pub steps: Vec<KnotPlanStep>,
}

/// One step of a [`KnotPlan`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KnotPlanStep {
    /// What the step does ("cross over the body"), for messages and tests.
    pub name: String,
    /// The move or hold.
    pub action: PlanAction,
    /// The crossing check that runs once this step has ended, if any (a check rides on the
    /// step after the move that makes its crossing: the tail lags its target).
    #[serde(default)]
    pub check: Option<PlanCheck>,
}

/// A move of the tail's target to a [`PlanTarget`] at the tie's speed, or a hold (s).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum PlanAction {
    /// Move the target to this point.
    Move(PlanTarget),
    /// Hold the target still for this many seconds (≥ 0).
    Hold(f64),
}

/// Where a move goes, in the units of the module docs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum PlanTarget {
    /// (a + along·R, aside·R, 0)·L.
    Sweep {
        /// Along the body, fraction of R.
        along: f64,
        /// To the side, fraction of R.
        aside: f64,
    },
    /// (0, aside_r, ±up_r) local radii from the body at a + past_crossover.
    Arc {
        /// How far tail-ward of the crossover (fraction of L; negative: head-ward).
        past_crossover: f64,
        /// To the side (local radii).
        aside_r: f64,
        /// Up, mirrored (local radii).
        up_r: f64,
    },
    /// (0, 0, ±up_r) mean radii from the largest loop's centroid.
    LoopCentroid {
        /// Up, mirrored (mean radii).
        up_r: f64,
    },
    /// (0, 0, ±up_r) mean radii from the previous target.
    Beyond {
        /// Up, mirrored (mean radii).
        up_r: f64,
    },
}

/// A crossing check as written in a plan file: its name and how the tail's crossings seen
/// from above begin, walking from the crossover to the tail.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanCheck {
    /// What the check is of ("the crossover").
    pub name: String,
    /// The crossings, as written (flipped for the mirror image).
    pub expected: Vec<Layer>,
}

/// Most crossings a check may list (those a [`crate::LayerCode`] keeps).
const MAX_CHECKED_CROSSINGS: usize = 32;

impl KnotPlan {
    /// Parses a plan file's text and checks it ([`KnotPlan::check`]).
    pub fn parse(text: &str) -> Result<Self, String> {
        let plan: Self = ron::from_str(text).map_err(|e| e.to_string())?;
        plan.check()?;
        Ok(plan)
    }

    /// Says what is wrong with the plan, if anything: a knot name that is not a Rolfsen name
    /// (crossings `_` index), no steps, a step without a name, a number that is not finite,
    /// a negative hold, or a check of no crossings or of more than 32.
    pub fn check(&self) -> Result<(), String> {
        let rolfsen = self.knot.split_once('_').is_some_and(|(c, i)| {
            [c, i].iter().all(|s| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()))
        });
        if !rolfsen {
            return Err(format!("knot {:?} is not a Rolfsen name such as \"6_2\"", self.knot));
        }
        if self.steps.is_empty() {
            return Err("the plan has no steps".into());
        }
        for (k, step) in self.steps.iter().enumerate() {
            let at = |what: &str| format!("step {} ({:?}): {what}", k + 1, step.name);
            if step.name.trim().is_empty() {
                return Err(at("a step needs a name"));
            }
            let numbers: &[f64] = match &step.action {
                PlanAction::Hold(s) if *s < 0.0 => return Err(at("a negative hold")),
                PlanAction::Hold(s) => &[*s],
                PlanAction::Move(PlanTarget::Sweep { along, aside }) => &[*along, *aside],
                PlanAction::Move(PlanTarget::Arc { past_crossover, aside_r, up_r }) => {
                    &[*past_crossover, *aside_r, *up_r]
                }
                PlanAction::Move(
                    PlanTarget::LoopCentroid { up_r } | PlanTarget::Beyond { up_r },
                ) => &[*up_r],
            };
            if numbers.iter().any(|x| !x.is_finite()) {
                return Err(at("a number that is not finite"));
            }
            if let Some(check) = &step.check {
                let n = check.expected.len();
                if n == 0 || n > MAX_CHECKED_CROSSINGS {
                    return Err(at("a check lists 1 to 32 crossings"));
                }
            }
        }
        Ok(())
    }

    /// The plan as the tie executes it with the crossover at `at` (fraction of L), the target
    /// moving at `speed` (cm/s), mirrored in z when `mirrored` (offsets up become down and
    /// every checked crossing flips).
    pub fn tie_plan(&self, at: f64, speed: f64, mirrored: bool) -> TiePlan {
        let z = if mirrored { -1.0 } else { 1.0 };
        let rest = 1.0 - at;
        let waypoint = |target: PlanTarget| match target {
            PlanTarget::Sweep { along, aside } => {
                Waypoint::BodyLengths([at + along * rest, aside * rest, 0.0])
            }
            PlanTarget::Arc { past_crossover, aside_r, up_r } => Waypoint::FromArc {
                at: at + past_crossover,
                offset_radii: [0.0, aside_r, z * up_r],
            },
            PlanTarget::LoopCentroid { up_r } => {
                Waypoint::FromLoopCentroidRadii([0.0, 0.0, z * up_r])
            }
            PlanTarget::Beyond { up_r } => Waypoint::FromTargetRadii([0.0, 0.0, z * up_r]),
        };
        let steps = self.steps.iter().map(|step| PlanStep {
            name: step.name.clone(),
            step: match step.action {
                PlanAction::Move(target) => ScriptStep::Move { to: waypoint(target), speed },
                PlanAction::Hold(seconds) => ScriptStep::Hold(seconds),
            },
            check: step.check.as_ref().map(|check| CrossingCheck {
                name: check.name.clone(),
                expected: check
                    .expected
                    .iter()
                    .map(|&l| if mirrored { l.flipped() } else { l })
                    .collect(),
            }),
        });
        TiePlan { steps: steps.collect() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_plans_parse_and_check() {
        let overhand = KnotPlan::parse(OVERHAND).expect("overhand.ron");
        assert_eq!((overhand.knot.as_str(), overhand.handedness), ("3_1", Some(Handedness::Right)));
        let eight = KnotPlan::parse(FIGURE_EIGHT).expect("figure_eight.ron");
        assert_eq!((eight.knot.as_str(), eight.handedness), ("4_1", None));
    }

    #[test]
    fn a_bad_plan_is_refused_with_its_step() {
        let plan = |knot: &str, steps: &str| {
            format!("(knot: {knot:?}, handedness: None, steps: [{steps}])")
        };
        let hold = |s: &str| format!("(name: \"wait\", action: Hold({s}))");
        assert!(KnotPlan::parse(&plan("6_2", &hold("1.0"))).is_ok());
        let refused = |text: String| KnotPlan::parse(&text).expect_err(&text);
        assert!(refused(plan("six", &hold("1.0"))).contains("Rolfsen"));
        assert!(refused(plan("6_2", "")).contains("no steps"));
        assert!(refused(plan("6_2", &hold("-1.0"))).contains("step 1 (\"wait\"): a negative hold"));
        assert!(refused(plan("6_2", &hold("inf"))).contains("not finite"));
        let unchecked =
            "(name: \"x\", action: Hold(1.0), check: Some((name: \"c\", expected: [])))";
        assert!(refused(plan("6_2", unchecked)).contains("1 to 32"));
        assert!(
            refused(plan("6_2", "(name: \"x\", action: Hold(1.0), speed: 2.0)")).contains("speed")
        );
    }

    #[test]
    fn the_mirror_image_negates_every_height_and_flips_every_check() {
        let plan = KnotPlan::parse(FIGURE_EIGHT).expect("figure_eight.ron");
        let (plain, mirrored) = (plan.tie_plan(0.3, 5.0, false), plan.tie_plan(0.3, 5.0, true));
        for (p, m) in plain.steps.iter().zip(&mirrored.steps) {
            let height = |s: &PlanStep| match s.step {
                ScriptStep::Move { to: Waypoint::FromArc { offset_radii, .. }, .. }
                | ScriptStep::Move { to: Waypoint::FromLoopCentroidRadii(offset_radii), .. }
                | ScriptStep::Move { to: Waypoint::FromTargetRadii(offset_radii), .. } => {
                    offset_radii[2]
                }
                _ => 0.0,
            };
            assert_eq!(height(p), -height(m), "{}", p.name);
            let flipped =
                p.check.as_ref().map(|c| c.expected.iter().map(|l| l.flipped()).collect());
            assert_eq!(m.check.as_ref().map(|c| c.expected.clone()), flipped, "{}", p.name);
        }
    }
}
