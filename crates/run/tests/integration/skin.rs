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
            let coefficients = rows.coefficients(i).expect("the row exists");
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
