//! `cargo xtask family --scenario data/scenarios/pole.ron --measure cylinder [--rounding N]`:
//! a knot tied around a still cylinder and slid along it (docs/physics.md, "A knot around a
//! pole"), on each member and its rounding perturbations (`family_cases.rs`): the slide's
//! knot measures ([`KnotRun`]) beside the knot's turns about the cylinder and its travel
//! along it ([`KnotAroundCylinder`]).

use glam::DVec3;
use hagfish_bench_support::Variant;
use hagfish_report::{KnotAroundCylinder, KnotRun, SlideBounds};
use hagfish_scenario::{LoadedScenario, ObstacleSpec};

use crate::family::{Runner, run_judged};
use crate::family_cases::Case;

/// The table's header.
const HEADER: &str = "| variant | tied at (s) | held | turns about the cylinder (slide start, \
     least) | slide (s) | travel along the cylinder (cm) | travel along the body (L) | nearest \
     core end (L) | speed (cm/s) | mean slide force \\|f\\| (dyn·cm) | max penetration (% r) \
     |\n|---|---|---|---|---|---|---|---|---|---|---|";

/// The bounds a run is judged by: the trefoil's on what it shares with the thesis run (held,
/// to the head, penetration, limits) — not where it was tied, how far or how fast it slid,
/// which the cylinder changes and the table shows — and around the cylinder in every slide
/// frame.
const BOUNDS: SlideBounds = SlideBounds {
    name: "the pole's",
    tied_core_start: 0.0,
    travel: 0.0,
    speed: None,
    ..SlideBounds::TREFOIL
};

/// The axis (a point and a direction) of the first still cylinder of the scenario.
pub fn cylinder_axis(loaded: &LoadedScenario) -> Result<(DVec3, DVec3), String> {
    loaded
        .scenario
        .obstacles
        .iter()
        .find_map(|o| match o {
            ObstacleSpec::Cylinder { point, axis, .. } => {
                Some((DVec3::from(*point), DVec3::from(*axis)))
            }
            _ => None,
        })
        .ok_or_else(|| "--measure cylinder: the scenario has no still cylinder".into())
}

/// Runs every member (and its perturbations) and prints the table, then which runs miss the
/// bounds and why.
pub fn run(
    runner: &Runner<'_>,
    members: &[Variant],
    axis: (DVec3, DVec3),
    scenario_step: f64,
) -> Result<(), String> {
    let passing = format!("stay around the cylinder in every slide frame and pass {BOUNDS}");
    run_judged(runner, members, HEADER, &passing, |case| row(runner, case, axis, scenario_step))
}

/// The row of `case` and, when it misses the bounds, how.
fn row(
    runner: &Runner<'_>,
    case: &Case<'_>,
    axis: (DVec3, DVec3),
    scenario_step: f64,
) -> (String, Option<String>) {
    let knot = runner.request.knot;
    let sign = (knot == "3_1").then_some(if case.variant.right_handed { 1.0 } else { -1.0 });
    let measured = case.run(runner, scenario_step, &[]).and_then(|out| {
        let slide = KnotRun::read(&out).map_err(|e| e.to_string())?;
        let around = KnotAroundCylinder::read(&out, axis.0, axis.1).map_err(|e| e.to_string())?;
        Ok((slide, around))
    });
    let (slide, around) = match measured {
        Ok(measured) => measured,
        Err(why) => {
            return (format!("| {} | — ({why}) | | | | | | | | | |", case.label()), Some(why));
        }
    };
    let mut failures = slide.failures(&BOUNDS, knot, sign);
    if around.least_turns < 1.0 - 1e-6 || around.shown < 1.0 {
        failures.push(format!(
            "least |turns| about the cylinder {:.2} (a knotted core on {:.0} % of the slide's \
             frames)",
            around.least_turns,
            100.0 * around.shown
        ));
    }
    let row = format!(
        "| {} | {:.1} | {:.0} % | {:.0}, {:.0} | {:.1}–{:.1} | {:.1} | {:.3} | {:.3} | {:.2} | \
         {:.0} | {:.2} |",
        case.label(),
        slide.tied_s,
        100.0 * slide.held(knot, sign),
        around.turns_at_slide_start,
        around.least_turns,
        slide.slide_s.0,
        slide.slide_s.1,
        around.axial_travel_cm,
        slide.travel,
        slide.nearest,
        slide.speed,
        around.slide_force,
        100.0 * slide.penetration,
    );
    (row, (!failures.is_empty()).then(|| failures.join("; ")))
}
