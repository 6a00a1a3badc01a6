//! The loose trefoil with friction against Audoly et al.'s F h²/B = ε⁴/2 ± μσε³
//! (`hagfish_validation::frictional_knot`).

use std::path::Path;

use hagfish_control::Phase;
use hagfish_sim::rows::Friction;
use hagfish_validation::frictional_knot::{
    AtEpsilon, Branch, FrictionalKnot, LoopMeasure, SIGMA, TIGHT_PULL_DYN, TIGHTENING_RAMP_S,
    TighteningStart, release, run,
};
use hagfish_validation::loose_knot::{self, Refinement};
use hagfish_validation::settle;

/// Closed onto the pull from the torus start, as the shipped study ramps it.
const TIGHTENING: Branch = Branch::Tightening { ramp_s: TIGHTENING_RAMP_S, from_dyn: None };

/// Opened onto the pull from the shipped study's tight knot.
const LOOSENING: Branch = Branch::Loosening { from_dyn: TIGHT_PULL_DYN };

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// The loop of a settled knot measured where its tangent is ⊥ the pull (every run here has
/// such a point).
fn perpendicular(knot: &FrictionalKnot) -> &LoopMeasure {
    knot.at_perpendicular().expect("a point of the loop ⊥ the pull")
}

/// At a pull of 20 dyn and μ = 0.02 and 0.05, on both branches: the friction term has
/// Audoly's sign on each branch, is linear in μ on the loosening branch (the friction numbers
/// at the two μ within 10 % of each other; measured −1.369, −1.363) and of one size on both
/// branches at μ = 0.05 (within 10 %; measured +1.340, −1.363): the form of their law, with
/// σ = 0.66–0.67 rather than 0.492. From the torus start the tightening branch is not linear
/// in μ: the loop closes onto +1.157 at μ = 0.02 against +1.341 at 0.05 (held 120 s; after the
/// scenario's 40 s it was still closing, at +1.363); from a looser loop +1.27–1.29 and +1.34
/// (`TighteningStart::Looser`), docs/validation.md, "Loose trefoil with friction".
#[test]
fn the_frictional_loose_trefoil_holds_its_loop_by_a_term_of_audolys_form() {
    let cases = [(TIGHTENING, 0.02), (TIGHTENING, 0.05), (LOOSENING, 0.02), (LOOSENING, 0.05)];
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
            perpendicular(knot).loop_radius_cm,
            perpendicular(knot).epsilon,
            perpendicular(knot).friction_number,
            SIGMA * perpendicular(knot).friction_number.abs()
        );
    }
    let [tight_low, tight_high, loose_low, loose_high] =
        [0, 1, 2, 3].map(|k| perpendicular(&knots[k]).friction_number);
    assert!(tight_low > 0.0 && tight_high > 0.0, "tightening: {tight_low}, {tight_high}");
    assert!(loose_low < 0.0 && loose_high < 0.0, "loosening: {loose_low}, {loose_high}");
    assert!((loose_low / loose_high - 1.0).abs() < 0.1, "linear in μ: {loose_low}, {loose_high}");
    assert!((tight_high / -loose_high - 1.0).abs() < 0.1, "symmetric: {tight_high}, {loose_high}");
    for knot in &knots {
        assert_the_first_integral_measures_the_loop_as_its_perpendicular_points_do(knot);
    }
}

/// The loop's first integral H gives the loop radius √(B/(2H)) that the curvature at its
/// points ⊥ the pull gives (the two agree at leading order in h/R): the friction numbers of
/// the two measures within 2 % (measured within 0.1 % at ε ≈ 0.1, 0.5 % at 0.2, 2.3 % at 0.3;
/// `cargo xtask audoly`, docs/validation.md).
fn assert_the_first_integral_measures_the_loop_as_its_perpendicular_points_do(
    knot: &FrictionalKnot,
) {
    let by_integral = knot.first_integral.expect("the loop has joints outside the braid");
    let at_perpendicular = perpendicular(knot);
    let ratio = by_integral.friction_number / at_perpendicular.friction_number;
    assert!((ratio - 1.0).abs() < 0.02, "{knot:?}");
}

/// The model is similar under h → h/2, F → 4F (B, L and the bodies per length of rod kept,
/// the bodies doubled): the loose trefoil loosened to 20 dyn on the rod of half the shipped
/// radius (800 bodies, h = 0.01 cm, time step 0.01 s) settles at the ε of the shipped rod
/// loosened to 5 dyn, with the same friction number (measured ε 0.10089 and 0.10088,
/// numbers −1.2589 and −1.2587). So the refinement of the frictionless check, which halves h
/// at a fixed pull, moves the friction law along ε rather than refining it.
#[test]
fn halving_the_radius_at_four_times_the_pull_gives_the_same_frictional_knot() {
    let friction = Friction::pyramid(0.05, 8);
    let cases =
        [(20.0, hagfish_validation::loose_knot::REFINEMENTS[1]), (5.0, Refinement::default())];
    let knots: Vec<FrictionalKnot> = std::thread::scope(|scope| {
        let runs: Vec<_> = cases
            .iter()
            .map(|&(t, r)| scope.spawn(move || run(root(), (LOOSENING, t), friction, r)))
            .collect();
        runs.into_iter().map(|r| r.join().expect("a run").expect("settles")).collect()
    });
    let [thin, shipped] = [&knots[0], &knots[1]];
    println!("h = 0.01 cm at 20 dyn: {thin:?}\nh = 0.02 cm at 5 dyn: {shipped:?}");
    let (thin_loop, shipped_loop) = (perpendicular(thin), perpendicular(shipped));
    assert!((thin_loop.epsilon / shipped_loop.epsilon - 1.0).abs() < 1e-3, "{thin:?} {shipped:?}");
    let ratio = thin_loop.friction_number / shipped_loop.friction_number;
    assert!((ratio - 1.0).abs() < 0.01, "{thin:?} {shipped:?}");
}

/// The excess over Audoly's σ is not a resolution error of the chain: at the shipped rod
/// radius (h = 0.02 cm) twice the bodies (800, 3.75 h each) leave the loosening friction
/// number within 2 % (measured −1.363 and −1.355; docs/validation.md, "Loose trefoil with
/// friction").
#[test]
fn at_the_shipped_rod_radius_the_friction_number_is_converged_in_the_bodies() {
    let friction = Friction::pyramid(0.05, 8);
    let finer = Refinement { bodies: Some(800), ..Refinement::default() };
    let numbers: Vec<f64> = std::thread::scope(|scope| {
        let runs: Vec<_> = [Refinement::default(), finer]
            .iter()
            .map(|&r| scope.spawn(move || run(root(), (LOOSENING, 20.0), friction, r)))
            .collect();
        runs.into_iter()
            .map(|r| perpendicular(&r.join().expect("a run").expect("settles")).friction_number)
            .collect()
    });
    println!("loosening friction numbers at 400 and 800 bodies, h = 0.02 cm: {numbers:?}");
    assert!((numbers[1] / numbers[0] - 1.0).abs() < 0.02, "{numbers:?}");
}

/// Audoly et al.'s loosening lock: the knot tightened by 100 dyn and let go (F = 0) opens until
/// ε = 2μσ, and not at all where μ ≥ ε₀/(2σ). At μ = 0.11 it opens (measured 12.9 %, onto
/// ε = 0.130: σ' = ε/(2μ) = 0.592); at μ = 0.125 it is locked (1.1 %: the loop's elastic
/// give as the pull goes, 1.0–1.2 % at every μ from 0.117 to 0.2). The lock's law holds with
/// the σ' of the opened knot: ε₀/(2σ') of the locked knot lies within the bracket (measured
/// 0.114), where Audoly's σ = 0.492 puts it at 0.1375, beyond it. And σ' is the opened
/// braid's own normal force N h²/(Bε³) (measured 0.581): the loop opened until friction held
/// Coulomb's μN. The bracket in finer steps, on 800 bodies, at h = 0.01 s and with E = 16
/// edges: docs/validation.md, "The loosening lock".
#[test]
fn a_knot_let_go_locks_where_mu_reaches_its_epsilon_over_two_sigma() {
    let [opens, locks] = std::thread::scope(|scope| {
        [0.11, 0.125]
            .map(|mu| {
                scope
                    .spawn(move || release(root(), Friction::pyramid(mu, 8), Refinement::default()))
            })
            .map(|run| run.join().expect("a run").expect("settles"))
    });
    for knot in [&opens, &locks] {
        println!(
            "μ = {}: let go at R = {:.4} cm (ε₀ = {:.4}), settled at R = {:.4} cm (ε = {:.4}): \
             opened {:.2} %; Audoly's lock ε₀/(2σ) = {:.4}",
            knot.let_go.coefficient,
            knot.let_go_loop().loop_radius_cm,
            knot.let_go_loop().epsilon,
            knot.settled_loop().loop_radius_cm,
            knot.settled_loop().epsilon,
            100.0 * knot.opening(),
            knot.lock_coefficient()
        );
    }
    assert!(opens.opening() > 0.05, "μ = 0.11 opens: {}", opens.opening());
    assert!(locks.opening() < 0.02, "μ = 0.125 is locked: {}", locks.opening());
    let sigma = opens.settled_loop().epsilon / (2.0 * opens.settled.coefficient);
    let lock = locks.let_go_loop().epsilon / (2.0 * sigma);
    println!("σ' = {sigma:.3} of the opened knot; its lock ε₀/(2σ') = {lock:.4}");
    assert!((0.11..0.125).contains(&lock), "the lock by σ' = {sigma}: μ = {lock}");
    let braid = SIGMA * opens.settled_loop().normal_force_number;
    assert!((braid / sigma - 1.0).abs() < 0.05, "σ' = {sigma}, the braid's N h²/(Bε³) {braid}");
}

/// `cargo xtask audoly`'s runs at μ = 0.1 and `epsilon` with a loop of `loop_radius_cm`, the
/// tightening one ramped over 60 s: (tightening, loosening).
fn at_epsilon(epsilon: f64, loop_radius_cm: f64) -> (AtEpsilon, AtEpsilon) {
    let b = loose_knot::bending_stiffness(root()).expect("the rod file");
    let (tightening, loosening) =
        AtEpsilon::both_branches((0.1, epsilon), loop_radius_cm, b, (60.0, TighteningStart::Torus));
    (tightening, loosening.expect("not locked: μ < ε/(2σ)"))
}

/// The loosening number grows with ε (docs/validation.md, "Loose trefoil with friction"):
/// at μ = 0.1 and R₀ = 2 cm, −1.187 at ε = 0.118 and −1.465 at ε = 0.220 (σ' 0.58 → 0.72),
/// where Audoly's law, a leading order in ε, has −1 at both.
#[test]
fn the_loosening_friction_number_grows_with_epsilon() {
    let [loose, tight] = std::thread::scope(|scope| {
        [0.1, 0.2]
            .map(|epsilon| scope.spawn(move || at_epsilon(epsilon, 2.0).1.run(root(), 8)))
            .map(|run| run.join().expect("a run").expect("settles"))
    });
    println!("{loose:?}\n{tight:?}");
    let (looser, tighter) = (perpendicular(&loose), perpendicular(&tight));
    assert!(looser.friction_number < 0.0 && tighter.friction_number < 0.0, "{loose:?} {tight:?}");
    let growth = tighter.friction_number.abs() - looser.friction_number.abs();
    assert!(tighter.epsilon > looser.epsilon + 0.05 && growth > 0.15, "{loose:?} {tight:?}");
}

/// Ramped over 60 s the tightening pull closes the loop quasi-statically: at ε ≈ 0.19 the
/// number is the same with the rod and loop of R₀ = 2 and 1.5 cm within 2 % (measured +1.668,
/// +1.674), where the 1 s ramp's dynamic closing gives +1.273 and +1.208.
#[test]
fn ramped_slowly_the_tightening_number_is_the_same_at_two_loop_radii() {
    let [wide, narrow] = std::thread::scope(|scope| {
        [2.0, 1.5]
            .map(|loop_radius| scope.spawn(move || at_epsilon(0.2, loop_radius).0.run(root(), 8)))
            .map(|run| run.join().expect("a run").expect("settles"))
    });
    println!("{wide:?}\n{narrow:?}");
    let (wide_number, narrow_number) =
        (perpendicular(&wide).friction_number, perpendicular(&narrow).friction_number);
    assert!(wide_number > 1.0, "{wide:?}");
    assert!((narrow_number / wide_number - 1.0).abs() < 0.02, "{narrow:?}");
}

/// The excess of the friction number over Audoly's 1 is friction's own: the frictionless
/// control (the same rod, h = 0.08 cm, pulled at F₀ = B/(2R²) for the loosening run's loop
/// R = 1.649 cm) holds the law's ½ (measured F₀R₀²/B = 0.4997), so against it the number
/// moves by 0.001 (−1.465 → −1.464). And it is the braid's normal force N: friction holds
/// 0.94 of Coulomb's μN (normal-force number 1.560), and the frictionless control's braid
/// already carries 1.733 times Audoly's σBε³/h² (docs/validation.md, "Loose trefoil with
/// friction").
#[test]
fn against_its_frictionless_control_the_loosening_number_keeps_its_excess() {
    let run = at_epsilon(0.2, 2.0).1;
    let knot = run.run(root(), 8).expect("settles");
    let control = knot.frictionless_control(root(), run.refinement()).expect("settles");
    let controlled = knot.controlled_friction_number(&control).expect("a ⊥ measure");
    println!("{knot:?}\n{control:?}\ncontrolled {controlled:+.4}");
    let measured = perpendicular(&knot);
    assert!((control.tension_number - 0.5).abs() < 0.01, "{control:?}");
    assert!((control.loop_radius_cm / measured.loop_radius_cm - 1.0).abs() < 0.01, "{control:?}");
    assert!((controlled - measured.friction_number).abs() < 0.02, "{controlled} {knot:?}");
    assert!(controlled < -1.3, "the excess over Audoly's −1 stays: {controlled}");
    // Coulomb's bound |F − H| ≤ μN, nearly reached: the contacts slide along the strands.
    let held = -measured.friction_number / measured.normal_force_number;
    assert!((0.85..=1.0).contains(&held), "friction holds {held} of μN: {knot:?}");
    assert!(control.normal_force_number > 1.5, "the frictionless braid's N: {control:?}");
    assert_the_first_integral_measures_the_loop_as_its_perpendicular_points_do(&knot);
}

/// The loosening branch at μ = 0.2, which leaves no point of the loop ⊥ the pull outside the
/// braid, measured by the loop's first integral: the target ε = 0.3 (R₀ = 2 cm, h = 0.18 cm)
/// opens onto ε ≈ 0.37 with a friction number of about −1.6 (measured −1.594; −1.343 at
/// ε = 0.27 and −1.743 at 0.47), beyond Audoly's −1 as every measured branch is
/// (docs/validation.md, "Loose trefoil with friction").
#[test]
fn the_loosening_branch_at_mu_two_tenths_holds_the_excess_of_the_others() {
    let b = loose_knot::bending_stiffness(root()).expect("the rod file");
    let (_, loosening) =
        AtEpsilon::both_branches((0.2, 0.3), 2.0, b, (60.0, TighteningStart::Torus));
    let knot = loosening.expect("not locked at ε = 0.3").run(root(), 8).expect("settles");
    println!("{knot:?}");
    let loop_measure = knot.first_integral.expect("the loop has joints outside the braid");
    assert!(loop_measure.friction_number < -1.2, "{knot:?}");
    assert!((0.3..0.45).contains(&loop_measure.epsilon), "{knot:?}");
}

/// The tightening branch reached from a looser loop (`TighteningStart::Looser`) against the
/// torus start, its control: at μ = 0.2 and target ε = 0.3 (R₀ = 2 cm, h = 0.18 cm, 60 s
/// ramp) the loop opening from the torus stops inside the held range at +1.710, where the
/// looser start closes onto +1.988 (and μ = 0.1 onto +1.971: one number for both μ, as the
/// law's form has it; +1.87 … +2.06 over ramps of 20 and 60 s; docs/validation.md).
#[test]
fn from_a_looser_loop_the_tightening_branch_holds_more_than_from_the_torus() {
    let b = loose_knot::bending_stiffness(root()).expect("the rod file");
    let [torus, looser] = std::thread::scope(|scope| {
        [TighteningStart::Torus, TighteningStart::Looser]
            .map(|start| {
                let (tightening, _) = AtEpsilon::both_branches((0.2, 0.3), 2.0, b, (60.0, start));
                scope.spawn(move || tightening.run(root(), 8))
            })
            .map(|run| run.join().expect("a run").expect("settles"))
    });
    println!("{torus:?}\n{looser:?}");
    let (from_torus, from_looser) = (perpendicular(&torus), perpendicular(&looser));
    assert!(from_looser.friction_number > 1.8, "{looser:?}");
    assert!(from_looser.friction_number > from_torus.friction_number + 0.15, "{torus:?}");
    assert!(
        from_looser.loop_radius_cm > from_torus.loop_radius_cm,
        "the branch's loop is the widest held"
    );
    assert_the_first_integral_measures_the_loop_as_its_perpendicular_points_do(&looser);
}

/// The settled rod's centreline as `cargo xtask braid` exports it for a peer
/// (`Settled::body_ends`): one point more than the bodies, from the head end at the wall, each
/// a body's length from the one before (the bodies are rigid and jointed at their ends), to
/// the tail end where the pull acts; and bent (a second of the pull from the torus start).
#[test]
fn the_exported_centreline_runs_through_the_ends_of_the_bodies() {
    let mut loaded = loose_knot::scenario(root(), 10.0, Refinement::default()).expect("loads");
    let Some(Phase::Load(load)) = loaded.scenario.phases.first_mut() else {
        panic!("the loose trefoil starts with its load");
    };
    load.until.seconds = 1.0;
    loaded.scenario.duration_s = 2.0;
    let settled = settle(&loaded).expect("the load phase ends");
    let (ends, rod) = (settled.body_ends(), &settled.rod);
    assert_eq!(ends.len(), rod.body_count + 1);
    assert!(ends[0].length() < 1e-12, "the head end at the wall: {}", ends[0]);
    let ell = rod.segment_length_cm();
    for (k, pair) in ends.windows(2).enumerate() {
        let gap = pair[0].distance(pair[1]);
        assert!((gap - ell).abs() < 1e-9 * ell, "body {k}: ends {gap} cm apart, its length {ell}");
    }
    assert!(ends[rod.body_count].distance(settled.tail_end()) < 1e-12);
    let span = ends[0].distance(ends[rod.body_count]);
    assert!(span < 0.9 * rod.length_cm, "the rod is bent: its ends {span} cm apart");
}
