//! Self contact in the full pipeline, along the first 20 s of `data/scenarios/form.ron` at
//! h = 0.01 s, where the tail is driven around and across the body: the tubes barely
//! penetrate with self contact on and pass through each other with it off, no touching
//! pair of centreline points is ever missed by the contact records, and the records are as
//! deep as the search from every start on every segment pair.

use glam::DVec3;
use hagfish_control::PhasedController;
use hagfish_geometry::{Centreline, ContactDetector, DetectorOptions, closest_points};
use hagfish_scenario::{LoadedScenario, Override};
use hagfish_sim::{Attempt, ContactResolution, StepData, StepOptions, World};
use hagfish_tree::State;

fn forming_world(self_contact: bool) -> (World, PhasedController) {
    let loaded =
        LoadedScenario::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/form.ron"))
            .expect("form.ron loads");
    let model = loaded.body.to_model().expect("model");
    let options = StepOptions { self_contact, ..StepOptions::default() };
    let state = State::rest(&model);
    let world = World::new(model, options, state).expect("world");
    let controller = PhasedController::new(loaded.scenario.drag, loaded.scenario.phases.clone());
    (world, controller)
}

/// Deepest penetration relative to the local radius, and the mean over penetrating contacts,
/// measured by an independent detector on the current centreline.
fn penetration(
    centres: &[DVec3],
    radii: &[f64],
    lengths: &[f64],
    detector: &mut ContactDetector,
) -> Vec<f64> {
    let centreline = Centreline::new(centres, radii).expect("centreline");
    let mut contacts = Vec::new();
    detector.detect(&centreline, lengths, &mut contacts).expect("detect");
    contacts
        .iter()
        .filter(|c| c.gap < 0.0)
        .map(|c| -c.gap / (0.5 * (centreline.radius(c.u_a) + centreline.radius(c.u_b))))
        .collect()
}

fn run_twenty_seconds(self_contact: bool) -> (f64, f64) {
    let (mut world, mut controller) = forming_world(self_contact);
    let radii: Vec<f64> = world.model().bodies().iter().map(|b| b.radius).collect();
    let lengths: Vec<f64> = world.model().bodies().iter().map(|b| b.length).collect();
    let mut detector = ContactDetector::new(DetectorOptions::default()).expect("detector");
    let (mut worst, mut sum, mut count) = (0.0f64, 0.0, 0usize);
    let mut centres = Vec::new();
    for _ in 0..2000 {
        world.step(&mut controller).expect("step");
        world.body_centres(&mut centres);
        for depth in penetration(&centres, &radii, &lengths, &mut detector) {
            worst = worst.max(depth);
            sum += depth;
            count += 1;
        }
    }
    (worst, if count > 0 { sum / count as f64 } else { 0.0 })
}

#[test]
fn self_contact_keeps_penetration_below_two_percent_and_is_needed() {
    let (worst_on, mean_on) = run_twenty_seconds(true);
    let (worst_off, mean_off) = run_twenty_seconds(false);
    println!(
        "penetration relative to the radius: contact on max {:.2} % mean {:.3} %; off max {:.1} % mean {:.1} %",
        100.0 * worst_on,
        100.0 * mean_on,
        100.0 * worst_off,
        100.0 * mean_off
    );
    assert!(worst_on < 0.02, "penetration {worst_on} of the radius with self contact on");
    assert!(
        worst_off > 0.2,
        "without self contact the body should pass through itself: {worst_off}"
    );
}

/// Runs the first 2000 steps of the tangled trajectory and calls `check` with the step index,
/// the world's detector options and the step data of every 10th step (which hold the
/// centreline and contacts of that step's start state).
fn every_tenth_step(mut check: impl FnMut(usize, &DetectorOptions, &StepData)) {
    let (mut world, mut controller) = forming_world(true);
    for step in 0..2000 {
        world.step(&mut controller).expect("step");
        if step % 10 == 0 {
            check(step, &world.options().detector_options(world.model()), world.data());
        }
    }
}

#[test]
fn no_touching_pair_is_missed_along_a_tangled_trajectory() {
    let (mut checked_frames, mut touching_pairs) = (0, 0);
    every_tenth_step(|step, options, data| {
        let (cluster, index_gap) = (options.cluster_radius, options.index_gap as f64);
        let line = &data.centreline;
        let samples: Vec<(f64, DVec3)> = (0..=line.segment_count() * 8)
            .map(|i| i as f64 / 8.0)
            .map(|u| (u, line.point(u)))
            .collect();
        for (i, &(u_a, x_a)) in samples.iter().enumerate() {
            for &(u_b, x_b) in &samples[i + 1..] {
                // Well outside the chain-index exclusion, and truly overlapping.
                if u_b - u_a <= index_gap + 1.0
                    || (x_b - x_a).length() >= line.radius(u_a) + line.radius(u_b)
                {
                    continue;
                }
                touching_pairs += 1;
                // A record stands for every pair of its segment pair merged into its cluster.
                let covered = data.self_contacts.iter().any(|c| {
                    (c.u_a - u_a).abs() <= cluster + 1.0 && (c.u_b - u_b).abs() <= cluster + 1.0
                });
                assert!(
                    covered,
                    "step {step}: touching pair u = ({u_a}, {u_b}) has no contact record"
                );
            }
        }
        checked_frames += 1;
    });
    println!("{checked_frames} frames, {touching_pairs} touching sample pairs, all covered");
    assert!(touching_pairs > 100, "the trajectory must be tangled");
}

/// The detector searches a segment pair from every start of [`closest_points`] only when the
/// search from the chords' closest points finds no contact there. Against that full search on
/// every segment pair (outside the index gap), every ~10th frame of the tangled trajectory:
/// each contact it finds has a record within cluster radius + 1 in both parameters (the record
/// its pair's result is merged into) at most 1e-4 cm shallower (measured: 6e-14 cm here,
/// 2.3e-5 cm along `thesis_scripted.ron`).
#[test]
fn records_are_as_deep_as_the_search_from_every_start() {
    let (mut contacts, mut worst) = (0, 0.0_f64);
    every_tenth_step(|step, options, data| {
        let reach = options.cluster_radius + 1.0;
        let line = &data.centreline;
        for k_a in 0..line.segment_count() {
            for k_b in k_a + options.index_gap..line.segment_count() {
                let found = closest_points(&line.segment(k_a), &line.segment(k_b));
                let (u_a, u_b) = (k_a as f64 + found.s_a, k_b as f64 + found.s_b);
                let gap = found.distance_squared.sqrt() - line.radius(u_a) - line.radius(u_b);
                if gap >= options.margin || u_b - u_a <= options.index_gap as f64 {
                    continue;
                }
                contacts += 1;
                let record = data
                    .self_contacts
                    .iter()
                    .filter(|c| (c.u_a - u_a).abs() <= reach && (c.u_b - u_b).abs() <= reach)
                    .map(|c| c.gap)
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    record <= gap + 1e-4,
                    "step {step}: segments ({k_a}, {k_b}) reach gap {gap} at u = ({u_a}, {u_b}); \
                     the nearby records only {record}"
                );
                worst = worst.max(record - gap);
            }
        }
    });
    println!("{contacts} contacts of the full search; records at most {worst:.1e} cm shallower");
    assert!(contacts > 1000, "the trajectory must be tangled: {contacts}");
}

/// `form.ron` on ES103 at `body_count` bodies with the scenario `overrides` (as
/// `--set`), built as [`forming_world`].
pub(crate) fn forming_world_of(body_count: usize, overrides: &[&str]) -> (World, PhasedController) {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let text = std::fs::read_to_string(format!("{root}/data/hagfish/es103.ron")).expect("es103");
    assert!(text.contains(" body_count: 100"));
    let body = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("es103_{body_count}_bodies.ron"));
    let text = text.replace(" body_count: 100", &format!(" body_count: {body_count}"));
    std::fs::write(&body, text).expect("write the body");
    let body = format!("body={:?}", body.to_string_lossy());
    let sets: Vec<Override> = std::iter::once(body.as_str())
        .chain(overrides.iter().copied())
        .map(|set| Override::parse(set).expect("an override"))
        .collect();
    let loaded = LoadedScenario::load_with(format!("{root}/data/scenarios/form.ron"), &sets)
        .expect("form.ron loads");
    let model = loaded.body.to_model().expect("model");
    let state = State::rest(&model);
    let world = World::new(model, StepOptions::default(), state).expect("world");
    let controller = PhasedController::new(loaded.scenario.drag, loaded.scenario.phases.clone());
    (world, controller)
}

#[test]
fn a_fine_chain_resolves_its_contacts_every_one_and_a_half_bodies_on_request() {
    // ES103's body-relative cluster radius is already 1.5 bodies: nothing to resolve.
    let (mut es103, _) = forming_world_of(100, &[]);
    assert!(!es103.set_contact_resolution(ContactResolution::Chain).expect("ES103"));
    // At 300 bodies it is 4.7 bodies; step the forming knot to 20 s, where strands lie along
    // each other.
    let (mut world, mut controller) = forming_world_of(300, &[]);
    let coarse_radius = world.options().detector_options(world.model()).cluster_radius;
    assert!((coarse_radius - 4.6875).abs() < 1e-12, "{coarse_radius}");
    while world.state().t < 20.0 {
        world.step(&mut controller).expect("step");
    }
    // The contacts a step from that state works with (detected at its start), with the
    // body-relative radius, resolved, and body-relative again.
    let (start, saved) = (world.state().clone(), controller.state());
    let time_step = world.options().time_step;
    let mut contacts_of_a_step = |world: &mut World, contacts: ContactResolution| {
        world.set_state(start.clone()).expect("the start state");
        controller.restore(&saved).expect("the controller");
        world.attempt(&mut controller, Attempt { time_step, contacts }).expect("step");
        world.data().self_contacts.clone()
    };
    let coarse = contacts_of_a_step(&mut world, ContactResolution::BodyRelative);
    let resolved = contacts_of_a_step(&mut world, ContactResolution::Chain);
    let coarse_again = contacts_of_a_step(&mut world, ContactResolution::BodyRelative);
    println!("{} contacts at 4.7 bodies, {} at 1.5", coarse.len(), resolved.len());
    assert!(resolved.len() > coarse.len());
    // The same deepest record; every coarse record within the coarse radius of a resolved
    // one; no two resolved records within 1.5 bodies of each other in both parameters.
    let deepest =
        |c: &[hagfish_geometry::SelfContact]| c.iter().map(|c| c.gap).fold(f64::MAX, f64::min);
    assert_eq!(deepest(&coarse), deepest(&resolved));
    let within = |a: &hagfish_geometry::SelfContact, b: &hagfish_geometry::SelfContact, r: f64| {
        (a.u_a - b.u_a).abs() <= r && (a.u_b - b.u_b).abs() <= r
    };
    for c in &coarse {
        assert!(resolved.iter().any(|r| within(c, r, coarse_radius)), "{c:?} is not covered");
    }
    for (i, a) in resolved.iter().enumerate() {
        for b in &resolved[i + 1..] {
            assert!(!within(a, b, hagfish_sim::RESOLVED_CLUSTER_BODIES), "{a:?} and {b:?}");
        }
    }
    // Back to the body-relative radius: the very same records as before.
    assert_eq!(coarse_again, coarse);
}
