//! Choi, Tong, Jawed & Joo 2021's knot-tying case (J. Appl. Mech. 88:051010): their rod
//! (`data/rods/choi2021.ron`: L = 100 cm, h = 0.16 cm, ρ = 1.18 g/cm³, E = 1.8·10⁶ dyn/cm²)
//! started from their overhand knot with n = 1…4 turns (`data/knots/imc-der/`), μ = 0.1,
//! left 2 s at rest, then pulled tight with both ends clamped, each end moving at u.
//!
//! Here (`data/validation/overhand_pull.ron`) the head is held and the tail gripped and moved at 2u:
//! the same relative motion seen from their head end's frame (no drag, no gravity: the
//! equations do not change under a constant velocity). Measured each step: the end-to-end
//! distance, the grip's pull force (the multipliers of its rows), the deepest self
//! penetration and where the loop lies across the pull ([`knot_loop`]: whether it inverts). The pull stops at a force, before the inextensible chain runs out of slack.
//! Each step is taken as `hagfish run` takes it (`World::advance`): a rejected step is retried
//! as substeps, so that a loop's snap gets through.

use std::path::Path;
use std::time::Instant;

use glam::DVec3;
use hagfish_control::Phase;
use hagfish_knots::{KnotOptions, analyse_knot};
use hagfish_scenario::{LoadedScenario, Override};
use hagfish_sim::rows::grip_wrench;
use hagfish_sim::{IntervalMaxima, StepOutcome, StepTally, StopRequest};

use crate::error::ValidationError;
use crate::knot_loop::{self, ContactPoint};

/// The scenario file, relative to the workspace root.
pub const SCENARIO: &str = "data/validation/overhand_pull.ron";

/// How far the ends are pulled apart at most (cm): the rod's 100 cm less the least of their
/// starting distances (28 cm, n = 1), so that a pull ends on its force, not on its distance.
pub const MAX_PULL_CM: f64 = 72.0;

/// One step's measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PullSample {
    /// Time since the pull started (s).
    pub time_s: f64,
    /// Distance from the head end to the tail end (cm).
    pub end_to_end_cm: f64,
    /// The grip's force along the pull (dyn): the tension the ends feel.
    pub force_dyn: f64,
    /// Where the knot's loop lies across the pull, from its braid ([`knot_loop`]; cm).
    pub loop_offset_cm: Option<DVec3>,
    /// How far the gripped point is from its target at the step's start (cm): what the
    /// position update left off the grip's line, which its rows then take back at β/h. It
    /// grows with the square of the joints' rates as a knot tightens; the scenario's step
    /// acceptance bounds it (docs/decisions/0038-grip-drift-bounded-on-the-pulls.md).
    pub grip_error_cm: f64,
}

/// The grip's largest distance from its target in a pull.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GripError {
    /// The distance (cm).
    pub error_cm: f64,
    /// The end-to-end distance where it was (cm).
    pub at_cm: f64,
}

/// How a pull ended.
#[derive(Clone, Debug, PartialEq)]
pub enum PullEnd {
    /// The force reached the stop force.
    Force,
    /// The ends were [`MAX_PULL_CM`] further apart.
    Distance,
    /// A step failed (the simulator's error, in words): the samples end before it.
    Failed(String),
}

/// A knot pulled tight.
#[derive(Clone, Debug, PartialEq)]
pub struct PulledKnot {
    /// Turns n of the overhand knot.
    pub turns: usize,
    /// Speed of each end in Choi et al.'s frame (cm/s): the tail moves at twice it here.
    pub end_speed_cm_per_s: f64,
    /// The time step (s).
    pub time_step_s: f64,
    /// One sample per step of the pull.
    pub samples: Vec<PullSample>,
    /// The deepest self penetration over the pull, over the rod's radius (the rest before it
    /// takes up the starting curve's own overlaps: Choi et al.'s curves put strands up to 2 %
    /// of h into each other at 600 bodies).
    pub max_penetration_relative: f64,
    /// The knot at the start and at the end (Rolfsen names by the knot analysis).
    pub knots: (String, String),
    /// How the pull ended.
    pub end: PullEnd,
    /// Steps run (the rest and the pull).
    pub steps: u64,
    /// Steps of them rejected whole and retried as substeps (the scenario's step acceptance:
    /// `data/validation/overhand_pull.ron` keeps the penetration within 0.5 % of the radius).
    pub retried_steps: u64,
    /// Wall time of the steps (s).
    pub wall_s: f64,
}

/// The knot type of the world's body (its centres, closed over many directions).
fn knot_name(world: &hagfish_sim::World) -> String {
    let data = &world.data().tree;
    let centres: Vec<_> = (0..world.model().body_count()).map(|b| data.body_centre(b)).collect();
    analyse_knot(&centres, &KnotOptions::default())
        .map_or_else(|e| format!("unknown ({e})"), |report| report.knot.to_string())
}

/// The mean force over the last `2 ·` [`SMOOTHING_HALF_WIDTH_CM`] of pull, once the pull has
/// gone that far (the first step's force is the jerk of starting at full speed, not the
/// knot's).
fn trailing_mean_force(samples: &[PullSample]) -> Option<f64> {
    let last = samples.last()?.end_to_end_cm;
    let window = 2.0 * SMOOTHING_HALF_WIDTH_CM;
    if last - samples.first()?.end_to_end_cm < window {
        return None;
    }
    let recent = samples.iter().rev().take_while(|s| last - s.end_to_end_cm <= window);
    let (sum, count) = recent.fold((0.0, 0usize), |(sum, n), s| (sum + s.force_dyn, n + 1));
    Some(sum / count as f64)
}

/// Pulls the n-turn knot with each end at `end_speed_cm_per_s`, steps of `time_step_s`, until
/// the pull force, averaged over the last 0.5 cm of pull, reaches `stop_force_dyn` (or the ends
/// are [`MAX_PULL_CM`] further apart); `extra` overrides the scenario further (another rod:
/// `body="…"`, another μ: `friction=…`), after the knot's starting curve is set.
pub fn run(
    root: &Path,
    (turns, end_speed_cm_per_s): (usize, f64),
    time_step_s: f64,
    stop_force_dyn: f64,
    extra: &[Override],
) -> Result<PulledKnot, ValidationError> {
    let shape = format!(
        "initial_shape=Some(Polyline((file: \"../knots/imc-der/n{turns}.txt\", cm_per_unit: 100.0)))"
    );
    let mut sets = vec![Override::parse(&shape)?];
    sets.extend_from_slice(extra);
    let mut loaded = LoadedScenario::load_with(root.join(SCENARIO), &sets)?;
    let scenario = &mut loaded.scenario;
    scenario.time_step_s = time_step_s;
    let Some(Phase::Pull(pull)) = scenario.phases.last_mut() else {
        return Err(ValidationError::Scenario {
            path: loaded.path.clone(),
            reason: "its last phase is not a pull".into(),
        });
    };
    pull.speed_cm_per_s = 2.0 * end_speed_cm_per_s;
    pull.until.seconds = MAX_PULL_CM / pull.speed_cm_per_s;
    let last_phase = scenario.phases.len() - 1;
    let (mut world, mut controller) = loaded.build()?;
    let radius = world.model().bodies()[0].radius;
    let start = knot_name(&world);
    let clock = Instant::now();
    let (mut samples, mut deepest, mut end) = (Vec::new(), 0.0f64, PullEnd::Distance);
    let mut retried_steps = 0;
    // The loop's inputs, refilled each step.
    let (mut centres, mut contacts): (Vec<DVec3>, Vec<ContactPoint>) = (Vec::new(), Vec::new());
    // Until the last phase (the pull) is over; the phases before it rest with a still grip.
    // The step's worst values; its impulse sums are not read (made once: they are n-vectors).
    let mut tally = StepTally::default();
    while !controller.finished() {
        // Each step as `hagfish run` takes it: a rejected step is retried (as substeps, whose
        // last one's multipliers give the force below).
        tally.maxima = IntervalMaxima::default();
        let divisions = match world.advance(&mut controller, &mut tally, StopRequest::default()) {
            StepOutcome::Accepted | StepOutcome::ResolvedContacts => 1.0,
            StepOutcome::Substeps { divisions } => {
                retried_steps += 1;
                f64::from(divisions)
            }
            StepOutcome::Failed(error) => {
                end = PullEnd::Failed(error.to_string());
                break;
            }
            // No stop flag is given, so a step is never stopped.
            StepOutcome::Stopped => break,
        };
        let penetration = tally.maxima.self_penetration;
        let Some(anchor) = controller.progress().pull.filter(|a| a.phase == last_phase) else {
            continue;
        };
        deepest = deepest.max(penetration);
        let data = world.data();
        let Some(grip) = data.actuation.grip else { continue };
        let (force, _) =
            grip_wrench(&data.rows, data.solver.multipliers(), time_step_s / divisions);
        let direction = grip.velocity.normalize_or_zero();
        // The contacts and the body centres of the step's start, as the data holds them.
        centres.clear();
        centres.extend((0..world.model().body_count()).map(|b| data.tree.body_centre(b)));
        contacts.clear();
        contacts.extend(
            data.self_contacts.iter().map(|c| (c.u_a, c.u_b, 0.5 * (c.point_a + c.point_b))),
        );
        let sample = PullSample {
            time_s: world.state().t - anchor.since_s,
            end_to_end_cm: grip.point.length(),
            force_dyn: force.dot(direction),
            loop_offset_cm: knot_loop::loop_side(&centres, &contacts, direction)
                .map(|side| side.offset_cm),
            grip_error_cm: grip.point.distance(grip.target),
        };
        samples.push(sample);
        if trailing_mean_force(&samples).is_some_and(|force| force >= stop_force_dyn) {
            end = PullEnd::Force;
            break;
        }
    }
    let wall_s = clock.elapsed().as_secs_f64();
    Ok(PulledKnot {
        turns,
        end_speed_cm_per_s,
        time_step_s,
        samples,
        max_penetration_relative: deepest / radius,
        knots: (start, knot_name(&world)),
        end,
        steps: world.steps(),
        retried_steps,
        wall_s,
    })
}

/// Half the window of [`PulledKnot::smoothed_force`] in end-to-end distance (cm): a step's
/// force carries the stick and slip of the friction pyramid's rows (±10 % step to step at
/// h = 0.02 s), the mean over 0.5 cm of pull does not.
pub const SMOOTHING_HALF_WIDTH_CM: f64 = 0.25;

/// The largest turn of the loop about the pull within a time window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopTurn {
    /// The angle between the loop's directions across the pull at the window's ends (rad).
    pub angle_rad: f64,
    /// The end-to-end distance at the window's end (cm).
    pub at_cm: f64,
}

/// The largest fall of the smoothed force below the highest force before it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceDrop {
    /// The fall over the force before it, (F_max − F)/F_max.
    pub fraction: f64,
    /// The end-to-end distance where the force was highest before the fall (cm).
    pub from_cm: f64,
    /// The force there (dyn).
    pub from_dyn: f64,
}

impl PulledKnot {
    /// The mean pull force (dyn) over the samples whose end-to-end distance is within
    /// [`SMOOTHING_HALF_WIDTH_CM`] of `end_to_end_cm`, or `None` if there are none.
    pub fn smoothed_force(&self, end_to_end_cm: f64) -> Option<f64> {
        let near = self
            .samples
            .iter()
            .filter(|s| (s.end_to_end_cm - end_to_end_cm).abs() <= SMOOTHING_HALF_WIDTH_CM);
        let (sum, count) = near.fold((0.0, 0usize), |(sum, n), s| (sum + s.force_dyn, n + 1));
        (count > 0).then(|| sum / count as f64)
    }

    /// The range of end-to-end distances pulled through, less the smoothing window at each
    /// end (cm).
    pub fn smoothed_range(&self) -> Option<(f64, f64)> {
        let first = self.samples.first()?.end_to_end_cm + SMOOTHING_HALF_WIDTH_CM;
        let last = self.samples.last()?.end_to_end_cm - SMOOTHING_HALF_WIDTH_CM;
        (last > first).then_some((first, last))
    }

    /// The smoothed force every `spacing_cm` of end-to-end distance: `(distance, force)`.
    pub fn smoothed_curve(&self, spacing_cm: f64) -> Vec<(f64, f64)> {
        let Some((first, last)) = self.smoothed_range() else { return Vec::new() };
        let count = ((last - first) / spacing_cm).floor() as usize;
        (0..=count)
            .map(|k| first + k as f64 * spacing_cm)
            .filter_map(|e| self.smoothed_force(e).map(|f| (e, f)))
            .collect()
    }

    /// The largest angle the loop's direction across the pull turns through between two
    /// samples at most `window_s` apart: an inversion turns it by about π in the time of a
    /// snap; `None` without two samples that have a loop.
    pub fn largest_loop_turn(&self, window_s: f64) -> Option<LoopTurn> {
        let with_loop: Vec<(f64, f64, DVec3)> = (self.samples.iter())
            .filter_map(|s| s.loop_offset_cm.map(|o| (s.time_s, s.end_to_end_cm, o)))
            .collect();
        let mut largest: Option<LoopTurn> = None;
        for (k, &(t, at_cm, offset)) in with_loop.iter().enumerate() {
            let earlier = with_loop[..k].iter().rev().take_while(|(s, _, _)| t - s <= window_s);
            for &(_, _, before) in earlier {
                let angle_rad = before.angle_between(offset);
                if largest.is_none_or(|l| angle_rad > l.angle_rad) {
                    largest = Some(LoopTurn { angle_rad, at_cm });
                }
            }
        }
        largest
    }

    /// The largest distance of the grip from its target over the pull; `None` without samples.
    pub fn largest_grip_error(&self) -> Option<GripError> {
        let largest =
            self.samples.iter().max_by(|a, b| a.grip_error_cm.total_cmp(&b.grip_error_cm));
        largest.map(|s| GripError { error_cm: s.grip_error_cm, at_cm: s.end_to_end_cm })
    }

    /// The largest fall of the smoothed force (every `spacing_cm`) below its highest value
    /// before, counted from where the force first reaches `from_dyn` (the start of the pull,
    /// where the knot takes up the slack of its starting curve, is left out).
    pub fn largest_drop(&self, spacing_cm: f64, from_dyn: f64) -> Option<ForceDrop> {
        let curve = self.smoothed_curve(spacing_cm);
        let start = curve.iter().position(|&(_, f)| f >= from_dyn)?;
        let mut peak = curve[start];
        let mut largest = ForceDrop { fraction: 0.0, from_cm: peak.0, from_dyn: peak.1 };
        for &(e, f) in &curve[start..] {
            if f > peak.1 {
                peak = (e, f);
            }
            let fraction = (peak.1 - f) / peak.1;
            if fraction > largest.fraction {
                largest = ForceDrop { fraction, from_cm: peak.0, from_dyn: peak.1 };
            }
        }
        Some(largest)
    }
}

/// The spread of the smoothed force between `runs` (one knot pulled at several speeds) along
/// the pull: at every `spacing_cm` of end-to-end distance that every run pulled through, from
/// where the first run's smoothed force first reaches `from_dyn`, (max − min)/mean of the runs'
/// smoothed forces ([`PulledKnot::smoothed_force`]). It judges the speeds over the whole pull,
/// not only at a few forces, where a slip falls on one side of the point in one run and on
/// the other in the next. Empty for fewer than two runs or no common range.
pub fn spread_along(runs: &[&PulledKnot], spacing_cm: f64, from_dyn: f64) -> Vec<f64> {
    let ranges: Option<Vec<(f64, f64)>> = runs.iter().map(|r| r.smoothed_range()).collect();
    let (Some(ranges), Some(first)) = (ranges, runs.first()) else { return Vec::new() };
    if runs.len() < 2 {
        return Vec::new();
    }
    let start = first.smoothed_curve(spacing_cm).into_iter().find(|&(_, f)| f >= from_dyn);
    let Some((start, _)) = start else { return Vec::new() };
    let start = ranges.iter().fold(start, |s, &(lo, _)| s.max(lo));
    let end = ranges.iter().fold(f64::INFINITY, |e, &(_, hi)| e.min(hi));
    if end < start {
        return Vec::new();
    }
    let count = ((end - start) / spacing_cm).floor() as usize;
    (0..=count)
        .filter_map(|k| {
            let at = start + k as f64 * spacing_cm;
            let forces: Option<Vec<f64>> = runs.iter().map(|r| r.smoothed_force(at)).collect();
            forces.map(|forces| relative_spread(&forces))
        })
        .collect()
}

/// (max − min)/mean of `forces` (one per speed, at one end-to-end distance; NaN for none).
pub fn relative_spread(forces: &[f64]) -> f64 {
    let mean = forces.iter().sum::<f64>() / forces.len() as f64;
    let (lo, hi) = forces
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &f| (lo.min(f), hi.max(f)));
    (hi - lo) / mean
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    /// A loop drifting by 1° a sample that snaps over to the other side between two samples:
    /// the largest turn within a window that holds both is the snap's; without it, the drift
    /// over the window; without a loop in any sample, none.
    #[test]
    fn the_largest_loop_turn_is_the_snap() {
        let sample = |k: usize| {
            let angle = (k as f64).to_radians() + if k >= 30 { std::f64::consts::PI } else { 0.0 };
            PullSample {
                time_s: 0.02 * k as f64,
                end_to_end_cm: 30.0 + 0.01 * k as f64,
                force_dyn: 50.0,
                loop_offset_cm: Some(DVec3::new(0.0, angle.cos(), angle.sin())),
                grip_error_cm: 1e-4 * k as f64,
            }
        };
        let mut knot = PulledKnot {
            turns: 3,
            end_speed_cm_per_s: 0.3,
            time_step_s: 0.02,
            samples: (0..60).map(sample).collect(),
            max_penetration_relative: 0.0,
            knots: ("7_1".into(), "7_1".into()),
            end: PullEnd::Force,
            steps: 60,
            retried_steps: 0,
            wall_s: 1.0,
        };
        // Window 0.07 s: samples up to 3 apart (0.02 s each); across the snap the nearest
        // pair (29°, 210°) turns the most, by π − 1°.
        let turn = knot.largest_loop_turn(0.07).expect("loops");
        assert!((turn.angle_rad - (PI - 1f64.to_radians())).abs() < 1e-9, "{turn:?}");
        assert!((turn.at_cm - 30.3).abs() < 1e-9, "{turn:?}");
        assert_eq!(knot.largest_loop_turn(0.01), None, "no two samples within 0.01 s");
        let grip = knot.largest_grip_error().expect("samples");
        assert!((grip.error_cm - 59e-4).abs() < 1e-12 && (grip.at_cm - 30.59).abs() < 1e-9);
        knot.samples.truncate(30);
        let calm = knot.largest_loop_turn(0.07).expect("loops");
        assert!((calm.angle_rad - 3f64.to_radians()).abs() < 1e-9, "{calm:?}");
        knot.samples.iter_mut().for_each(|s| s.loop_offset_cm = None);
        assert_eq!(knot.largest_loop_turn(0.1), None);
    }

    /// Two pulls whose forces differ by 10 % everywhere (F = 10e and 11e dyn at end-to-end
    /// distance e cm) spread by 1/10.5 at every compared distance, from where the first reaches
    /// the force given to the end of the shorter pull; one pull alone has no spread.
    #[test]
    fn the_spread_along_the_pull_compares_every_common_distance() {
        let pull = |speed: f64, factor: f64, last_cm: f64| PulledKnot {
            turns: 2,
            end_speed_cm_per_s: speed,
            time_step_s: 0.02,
            samples: (0..=((last_cm - 30.0) * 100.0).round() as usize)
                .map(|k| {
                    let e = 30.0 + 0.01 * k as f64;
                    PullSample {
                        time_s: 0.02 * k as f64,
                        end_to_end_cm: e,
                        force_dyn: factor * e,
                        loop_offset_cm: None,
                        grip_error_cm: 0.0,
                    }
                })
                .collect(),
            max_penetration_relative: 0.0,
            knots: ("5_1".into(), "5_1".into()),
            end: PullEnd::Force,
            steps: 0,
            retried_steps: 0,
            wall_s: 0.0,
        };
        let (slow, fast) = (pull(0.3, 10.0, 40.0), pull(0.9, 11.0, 38.0));
        let spreads = spread_along(&[&slow, &fast], 0.25, 337.0);
        // The slow pull first reaches 337 dyn at 33.75 cm (337.5 there); the fast one ends at
        // 38 cm, smoothed to 37.75: 17 distances 0.25 cm apart.
        assert_eq!(spreads.len(), 17, "{spreads:?}");
        for spread in &spreads {
            assert!((spread - 1.0 / 10.5).abs() < 1e-9, "{spread}");
        }
        assert!(spread_along(&[&slow], 0.25, 337.0).is_empty());
        assert!(spread_along(&[&slow, &fast], 0.25, 1000.0).is_empty(), "never reaches it");
    }
}
