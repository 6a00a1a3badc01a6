//! The skin (docs/physics.md, "Skin") on the knot `form.ron` ties, the body given a skin by
//! the scenario: every self contact gets a compliant skin row beside its core row, each skin
//! row's impulse is the backward-Euler spring `h·k·max(0, −(g + h·ḋ))` with
//! `k = π p √(r_a r_b)` computed here from the scenario's pressure and the tube radii, and the
//! cores stay apart while the skins compress.

use hagfish_scenario::{LoadedScenario, Override};
use hagfish_sim::GroupForces;
use hagfish_sim::rows::RowGroup;

/// The skin of these tests: a quarter of the radius, 1000 dyn/cm².
const PRESSURE_DYN_PER_CM2: f64 = 1000.0;
const SKIN: &str = "skin=Some((thickness_fraction: 0.25, pressure_dyn_per_cm2: 1000.0))";

#[test]
fn each_skin_row_pushes_with_the_implicit_spring_of_its_contact() {
    let path = format!("{}/../../data/scenarios/form.ron", env!("CARGO_MANIFEST_DIR"));
    let overrides = [Override::parse(SKIN).expect("an override")];
    let loaded = LoadedScenario::load_with(&path, &overrides).expect("form.ron loads with a skin");
    let (mut world, mut forming) = loaded.build().expect("world builds");
    let h = world.options().time_step;
    let (mut springs_checked, mut compressed, mut deepest_core) = (0, 0, 0.0_f64);
    while world.state().t < 17.0 {
        world.step(&mut forming).expect("forming step");
        let data = world.data();
        deepest_core = deepest_core.max(data.report.max_self_penetration_relative);
        let (rows, lambda, qdot) = (&data.rows, data.solver.multipliers(), data.solver.velocity());
        let skin_rows = rows.sources().iter().filter(|s| s.tag == RowGroup::Skin.tag()).count();
        assert_eq!(skin_rows, data.self_contacts.len(), "one skin row per self contact");
        for (i, source) in rows.sources().iter().enumerate() {
            if source.tag != RowGroup::Skin.tag() {
                continue;
            }
            let contact = &data.self_contacts[source.id];
            let (r_a, r_b) =
                (data.centreline.radius(contact.u_a), data.centreline.radius(contact.u_b));
            let stiffness = std::f64::consts::PI * PRESSURE_DYN_PER_CM2 * (r_a * r_b).sqrt();
            let coefficients = rows.row(i).expect("the row exists").to_vec();
            let speed: f64 = coefficients.iter().zip(qdot).map(|(c, v)| c * v).sum();
            let expected = h * stiffness * (-(contact.gap + h * speed)).max(0.0);
            let tolerance = 1e-7 * (1.0 + expected.abs());
            assert!(
                (lambda[i] - expected).abs() < tolerance,
                "t = {}: contact {} λ = {:e}, spring h·k·δ⁺ = {expected:e}",
                world.state().t,
                source.id,
                lambda[i]
            );
            springs_checked += 1;
            compressed += usize::from(expected > 0.0);
        }
    }
    assert!(compressed > 100, "skins compressed in {compressed} of {springs_checked} rows");
    // The recorded contact force is the core rows' and the skin rows' together.
    let (data, dofs) = (world.data(), world.model().dof_count());
    let mut recorded = GroupForces::default();
    recorded.add_impulses(data, dofs);
    let (core, skin) = (
        data.solver.tag_impulse(RowGroup::Contact.tag()),
        data.solver.tag_impulse(RowGroup::Skin.tag()),
    );
    assert!(skin.iter().any(|&f| f != 0.0), "the last step's skins push");
    for ((r, c), k) in recorded.group(RowGroup::Contact).iter().zip(core).zip(skin) {
        assert_eq!(*r, 0.0 + c + k);
    }
    assert!(deepest_core < 0.02, "the cores kept apart: {deepest_core}");
    assert!(world.data().report.max_skin_compression > 0.0, "the tied knot presses its skins");
}

/// A step retried with its contacts at the chain's resolution has several records along each
/// stretch where two strands lie side by side, where the body-relative radius keeps one: all get
/// core rows, but only the records that radius keeps get springs, so the skin pushes as hard
/// as in the step it replaces. With a spring on every record the 300-body figure-eight's
/// retried steps in its slide penetrated 41–114 % of the radius where the step it replaced
/// penetrated 8.5 % (docs/physics.md, "Skin").
#[test]
fn a_step_retried_at_the_chain_resolution_keeps_the_skin_springs_of_the_body_relative_one() {
    use hagfish_sim::{Attempt, ContactResolution, World};
    // At 23 s of the forming knot 53 records touch at the body-relative radius, 412 at the
    // chain's; with a spring on every one the resolved step's skins pushed 3.2 times as hard.
    let (mut world, mut controller) = crate::self_contact::forming_world_of(300, &[SKIN]);
    while world.state().t < 23.0 {
        world.step(&mut controller).expect("forming step");
    }
    let (start, saved) = (world.state().clone(), controller.state());
    let time_step = world.options().time_step;
    // (records, skin rows, Σ skin impulse) of one attempt of the step from that state.
    let mut step_at = |world: &mut World, contacts: ContactResolution| {
        world.set_state(start.clone()).expect("the start state");
        controller.restore(&saved).expect("the controller");
        world.attempt(&mut controller, Attempt { time_step, contacts }).expect("step");
        let data = world.data();
        let skin_rows: Vec<usize> = (data.rows.sources().iter().enumerate())
            .filter(|(_, s)| s.tag == RowGroup::Skin.tag())
            .map(|(i, _)| i)
            .collect();
        let impulse: f64 = skin_rows.iter().map(|&i| data.solver.multipliers()[i]).sum();
        (data.self_contacts.len(), skin_rows.len(), impulse)
    };
    let coarse = step_at(&mut world, ContactResolution::BodyRelative);
    let resolved = step_at(&mut world, ContactResolution::Chain);
    println!("(records, springs, Σλ): body-relative {coarse:?}, chain {resolved:?}");
    assert!(coarse.2 > 0.0, "the skins are pressed");
    assert!(resolved.0 > 2 * coarse.0, "strands lie side by side: {resolved:?} {coarse:?}");
    assert!(resolved.1 < resolved.0, "only some resolved records carry a spring");
    assert!(resolved.1 <= coarse.1, "no more springs than the body-relative step's");
    let ratio = resolved.2 / coarse.2;
    assert!((0.8..1.25).contains(&ratio), "Σλ resolved / body-relative = {ratio}");
}

/// A rod has no skin to give: the scenario's skin on a rod body is refused at its position.
#[test]
fn a_skin_on_a_rod_is_refused() {
    let path = format!("{}/../../data/validation/cantilever.ron", env!("CARGO_MANIFEST_DIR"));
    let overrides = [Override::parse(SKIN).expect("an override")];
    let refused = LoadedScenario::load_with(&path, &overrides).map(|_| ());
    let message = refused.expect_err("refused").to_string();
    assert!(message.contains("a skin needs a hagfish body"), "{message}");
}

/// A skin's thickness is a fraction of the radius in (0, 1) and its pressure positive: other
/// values are refused, naming the field.
#[test]
fn a_skin_out_of_range_is_refused_with_its_field() {
    let path = format!("{}/../../data/scenarios/form.ron", env!("CARGO_MANIFEST_DIR"));
    for (value, field) in [
        ("(thickness_fraction: 1.0, pressure_dyn_per_cm2: 1000.0)", "thickness_fraction"),
        ("(thickness_fraction: 0.25, pressure_dyn_per_cm2: 0.0)", "pressure_dyn_per_cm2"),
    ] {
        let overrides = [Override::parse(&format!("skin=Some({value})")).expect("an override")];
        let refused = LoadedScenario::load_with(&path, &overrides).map(|_| ());
        let message = refused.expect_err("refused").to_string();
        assert!(message.contains(field), "{value}: {message}");
    }
}
