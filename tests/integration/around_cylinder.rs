//! A knot tied around a pole and slid along it by thigmotaxis with friction
//! (`data/scenarios/pole.ron`; docs/physics.md, "A knot around a pole"): on ES103 as written
//! and with its time step changed by 1 part in 10¹², the trefoil is tied with the pole inside
//! it (its core winds at least once about the pole's axis in every slide frame), and the slide
//! carries it ≥ 0.15 L along the pole, its core's head-ward end to within 0.05 L of the head.
//! The control run's slide rows may exert at most 10⁻⁶ dyn (the body passive, the tail pull
//! kept): its knot drifts (by −3.6 to +7.0 cm along the pole in the 20 s, on three rounding
//! replicates) but stays ≥ 0.15 L from the head.

use crate::common::run_scenario;
use glam::DVec3;
use hagfish_report::{KnotAroundCylinder, KnotRun};

/// ES103's length (cm).
const LENGTH_CM: f64 = 42.4;

/// Runs `pole.ron` into a fresh directory `name` with `--set` values `sets` and measures its
/// slide and its slide around the pole (the scenario's: along +x through (0, −1.9, 0)).
fn around(name: &str, sets: &[String]) -> (KnotRun, KnotAroundCylinder) {
    let dir = run_scenario(name, "data/scenarios/pole.ron", sets);
    let slide = KnotRun::read(&dir).unwrap_or_else(|e| panic!("{name}: {e}"));
    let around = KnotAroundCylinder::read(&dir, DVec3::new(0.0, -1.9, 0.0), DVec3::X)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    (slide, around)
}

#[test]
fn a_knot_tied_around_a_pole_slides_along_it_by_thigmotaxis() {
    let passive = "phases[2].Thigmotaxis.parameters.max_force_dyn=1e-6";
    let jobs: Vec<(u32, bool)> = (0..2).flat_map(|k| [(k, false), (k, true)]).collect();
    let results = std::thread::scope(|scope| {
        let handles: Vec<_> = jobs
            .iter()
            .map(|&(k, control)| {
                scope.spawn(move || {
                    let h = 0.01 * (1.0 + f64::from(k) * 1e-12);
                    let mut sets = vec![format!("time_step_s={h:?}")];
                    if control {
                        sets.push(passive.into());
                    }
                    around(&format!("pole_{k}_{control}"), &sets)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("a run")).collect::<Vec<_>>()
    });
    for (k, pair) in results.chunks(2).enumerate() {
        let [(slide, run), (passive, _)] = pair else { unreachable!("runs come in pairs") };
        let label = format!("δh/h = {k}e-12");
        assert!(slide.held("3_1", Some(1.0)) >= 0.99, "{label}: the trefoil was not held");
        assert!(run.shown == 1.0 && run.least_turns >= 1.0 - 1e-9, "{label}: {run:?}");
        assert!(slide.nearest <= 0.05, "{label}: the core came to {} L", slide.nearest);
        assert!(run.axial_travel_cm >= 0.15 * LENGTH_CM, "{label}: {run:?}");
        assert!(passive.nearest >= 0.15, "{label}: the passive knot came to {}", passive.nearest);
        assert!(slide.penetration < 0.02, "{label}: penetration {}", slide.penetration);
    }
}
