//! Friction on the self contacts in the full pipeline (docs/physics.md, "Friction: the cone
//! and its pyramid"): `form.ron` with μ = 0.3. Every self contact's impulse, summed over its
//! pyramid's edges, lies in Coulomb's cone, and friction does act: some contacts carry a
//! tangential impulse of more than half their cone's limit.

use glam::DVec3;
use hagfish_scenario::{LoadedScenario, Override};
use hagfish_sim::rows::{MAX_FRICTION_EDGES, RowGroup, contact_directions};

#[test]
fn self_contact_impulses_lie_in_the_friction_cone_and_friction_acts() {
    let path = format!("{}/../../data/scenarios/form.ron", env!("CARGO_MANIFEST_DIR"));
    let set = Override::parse("friction=Some((coefficient: 0.3))").expect("an override");
    let loaded = LoadedScenario::load_with(&path, &[set]).expect("form.ron with friction");
    let (mut world, mut forming) = loaded.build().expect("world builds");
    let friction = world.options().friction;
    let mu = friction.map_or(0.0, |f| f.coefficient);
    let (mut contacts_seen, mut gripping, mut worst) = (0, 0, 0.0_f64);
    let mut directions = [DVec3::ZERO; MAX_FRICTION_EDGES];
    while world.state().t < 18.0 {
        world.step(&mut forming).expect("forming step");
        let data = world.data();
        let (sources, lambda) = (data.rows.sources(), data.solver.multipliers());
        let mut row = 0;
        while row < sources.len() {
            if sources[row].tag != RowGroup::Contact.tag() {
                row += 1;
                continue;
            }
            let contact = &data.self_contacts[sources[row].id];
            let edges =
                contact_directions(contact.normal, contact.tangent_a, friction, &mut directions);
            let impulse: DVec3 = (0..edges).map(|k| lambda[row + k] * directions[k]).sum();
            let normal = impulse.dot(contact.normal);
            let tangent = (impulse - normal * contact.normal).length();
            worst = worst.max(tangent - mu * normal);
            contacts_seen += 1;
            gripping += usize::from(normal > 0.0 && tangent > 0.5 * mu * normal);
            row += edges;
        }
    }
    println!("{contacts_seen} contact-steps, {gripping} with friction above half its limit");
    assert!(worst <= 1e-12, "an impulse outside the cone by {worst:e}");
    assert!(
        contacts_seen > 1000 && gripping > 100,
        "{contacts_seen} contacts, {gripping} gripping"
    );
}
