//! The loose trefoil with friction against Audoly et al.'s F h²/B = ε⁴/2 ± μσε³
//! (`hagfish_validation::frictional_knot`).

use std::path::Path;

use hagfish_sim::rows::Friction;
use hagfish_validation::frictional_knot::{Branch, FrictionalKnot, SIGMA, run};
use hagfish_validation::loose_knot::Refinement;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// At a pull of 20 dyn and μ = 0.02 and 0.05, on both branches: the friction term has
/// Audoly's sign on each branch, is linear in μ (the friction numbers at the two μ within
/// 10 % of each other) and of one size on both branches (within 10 %): the form of their
/// law. Its size is not converged at this resolution: the friction numbers are 1.35–1.37,
/// σ = 0.67 rather than 0.492 (docs/validation.md, "Loose trefoil with friction").
#[test]
fn the_frictional_loose_trefoil_holds_its_loop_by_a_term_linear_in_mu_on_both_branches() {
    let cases = [
        (Branch::Tightening, 0.02),
        (Branch::Tightening, 0.05),
        (Branch::Loosening, 0.02),
        (Branch::Loosening, 0.05),
    ];
    let knots: Vec<FrictionalKnot> = std::thread::scope(|scope| {
        let runs: Vec<_> = cases
            .iter()
            .map(|&(branch, mu)| {
                let friction = Friction::pyramid(mu, 8);
                scope.spawn(move || run(root(), (branch, 20.0), friction, Refinement::default()))
            })
            .collect();
        runs.into_iter().map(|r| r.join().expect("a run").expect("settles")).collect()
    });
    for knot in &knots {
        println!(
            "{:?}, μ = {}: R = {:.4} cm, ε = {:.4}, friction number {:.3} (σ' = {:.3})",
            knot.branch,
            knot.coefficient,
            knot.loop_radius_cm,
            knot.epsilon,
            knot.friction_number,
            SIGMA * knot.friction_number.abs()
        );
    }
    let [tight_low, tight_high, loose_low, loose_high] =
        [0, 1, 2, 3].map(|k| knots[k].friction_number);
    assert!(tight_low > 0.0 && tight_high > 0.0, "tightening: {tight_low}, {tight_high}");
    assert!(loose_low < 0.0 && loose_high < 0.0, "loosening: {loose_low}, {loose_high}");
    assert!((tight_low / tight_high - 1.0).abs() < 0.1, "linear in μ: {tight_low}, {tight_high}");
    assert!((loose_low / loose_high - 1.0).abs() < 0.1, "linear in μ: {loose_low}, {loose_high}");
    assert!((tight_high / -loose_high - 1.0).abs() < 0.1, "symmetric: {tight_high}, {loose_high}");
}

/// Along the refinement of the frictionless check (the rod's radius halved with twice the
/// bodies, so the braid stays resolved by 7.5 bodies per radius) the loosening friction
/// number at 20 dyn and μ = 0.05 falls in size: −1.364 at 400 bodies (h = 0.02 cm), −1.259
/// at 800 (h = 0.01 cm); −0.915 at 1600 (35 min, not a test; docs/validation.md).
#[test]
fn the_frictional_trefoils_excess_over_audolys_sigma_falls_along_the_refinement() {
    let friction = Friction::pyramid(0.05, 8);
    let refinements = [Refinement::default(), hagfish_validation::loose_knot::REFINEMENTS[1]];
    let numbers: Vec<f64> = std::thread::scope(|scope| {
        let runs: Vec<_> = refinements
            .iter()
            .map(|&r| scope.spawn(move || run(root(), (Branch::Loosening, 20.0), friction, r)))
            .collect();
        runs.into_iter()
            .map(|r| r.join().expect("a run").expect("settles").friction_number)
            .collect()
    });
    println!("loosening friction numbers along the refinement: {numbers:?}");
    assert!(numbers[1] < 0.0 && numbers[1] > numbers[0], "{numbers:?}");
}

/// The excess over Audoly's σ is not a resolution error of the chain: at the shipped rod
/// radius (h = 0.02 cm) twice the bodies (800, 3.75 h each) leave the loosening friction
/// number within 2 % (measured −1.364 and −1.356), where halving h with them moves it by 8 %
/// (the test above; docs/validation.md, "Loose trefoil with friction").
#[test]
fn at_the_shipped_rod_radius_the_friction_number_is_converged_in_the_bodies() {
    let friction = Friction::pyramid(0.05, 8);
    let finer = Refinement { bodies: Some(800), ..Refinement::default() };
    let numbers: Vec<f64> = std::thread::scope(|scope| {
        let runs: Vec<_> = [Refinement::default(), finer]
            .iter()
            .map(|&r| scope.spawn(move || run(root(), (Branch::Loosening, 20.0), friction, r)))
            .collect();
        runs.into_iter()
            .map(|r| r.join().expect("a run").expect("settles").friction_number)
            .collect()
    });
    println!("loosening friction numbers at 400 and 800 bodies, h = 0.02 cm: {numbers:?}");
    assert!((numbers[1] / numbers[0] - 1.0).abs() < 0.02, "{numbers:?}");
}
