//! The loose trefoil under tension (`data/validation/loose_trefoil.ron`; Audoly, Clauvelin &
//! Neukirch, Phys. Rev. Lett. 99, 164301, 2007): a thin rod posed as an open trefoil, held at
//! the head, pulled at the tail by T along +X, frictionless self contact, settled.
//!
//! Away from the braid (the stretch where the strands touch) no force acts on the rod, and a
//! frictionless contact force is normal to it, so the Kirchhoff equations keep the first
//! integral `H = Bκ²/2 + Cτ²/2 + n·t` constant along the whole rod: `H = T` (its value on the
//! straight tail). Where the loop's tangent is perpendicular to the pull, `n·t → 0` at
//! leading order in h/R (h the rod's radius), so there `Bκ²/2 = T`: the loop's radius of
//! curvature R obeys `T R²/B = 1/2`.
//!
//! Measured on the settled chain:
//! - R where the tangent crosses ⊥ +X outside the braid (at least [`BRAID_MARGIN`] rod radii
//!   and [`BRAID_MARGIN_SEGMENTS`] body lengths of arc from any contact): the chain's segment directions are the tangents at the
//!   segments' midpoints, interpolated linearly to the crossing; the curvature `θ/(2ℓ)` of the
//!   bending joints (θ the angle between the segments a joint joins), interpolated likewise;
//! - `H/T` at every joint from the internal forces: `|m_bend|²/(2B) + m_twist²/(2C) + N`;
//! - the loop's H: its mean over the joints of the loop (the longest contact-free stretch
//!   between the rod's first and last contact, less the braid margin at both ends), where no
//!   force acts, so that H is the same at each of them ([`LoopFirstIntegral`]). With friction
//!   H jumps across the braid, and the loop's H, not the pull, sets its radius:
//!   `R = √(B/(2H))` at leading order, a measure of the loop that needs no point ⊥ the pull;
//! - the braid's total normal force N, the self-contact rows' multipliers summed over the
//!   time step and averaged over the last second ([`Settled::contact_normal_force_dyn`]):
//!   with friction μ the braid holds at most μN of the jump of H across it.

use std::path::Path;

use glam::DVec3;
use hagfish_anatomy::Body;
use hagfish_control::Phase;
use hagfish_knots::{KnotOptions, analyse_knot};
use hagfish_scenario::{InitialShape, LoadedScenario};
use hagfish_tree::JointKind;

use crate::check::Check;
use crate::error::ValidationError;
use crate::settle::{Settled, settle};

/// The scenario file, relative to the workspace root.
pub const SCENARIO: &str = "data/validation/loose_trefoil.ron";

/// How far (in rod radii of arc length) from every contact a point must be to count as
/// outside the braid; and at least [`BRAID_MARGIN_SEGMENTS`] body lengths ℓ, the chain's
/// own resolution (a body touched by a contact carries its force over its whole length).
/// The loop's points ⊥ the pull lie about (π/2)R = (π/2)h/ε² of arc from the braid's ends,
/// 17 h at ε = 0.3: 10 h left none to measure there (`cargo xtask audoly`). On the shipped
/// rods (h ≤ 0.04 cm) the margin in bodies is the larger one.
pub const BRAID_MARGIN: f64 = 4.0;

/// The least braid margin in body lengths ℓ.
pub const BRAID_MARGIN_SEGMENTS: f64 = 4.0;

/// What the settled loose knot measured.
#[derive(Clone, Debug, PartialEq)]
pub struct LooseKnot {
    /// The pull T it settled under (dyn).
    pub tension_dyn: f64,
    /// The rod's bending stiffness B (dyn·cm²).
    pub bending_stiffness_dyn_cm2: f64,
    /// The rod's radius h (cm).
    pub rod_radius_cm: f64,
    /// Radii of curvature (cm) where the loop's tangent is perpendicular to the pull, in
    /// order along the rod (two for a loop: where it rises and where it comes back).
    pub loop_radii_cm: Vec<f64>,
    /// The first integral at every joint, `H_j` (dyn).
    pub first_integral: Vec<f64>,
    /// Whether each joint lies outside the braid (see [`BRAID_MARGIN`]).
    pub outside_braid: Vec<bool>,
    /// Whether each joint is a bending joint.
    pub bending_joint: Vec<bool>,
    /// The first integral on the loop, `None` where the loop has no joint outside the braid.
    pub loop_first_integral: Option<LoopFirstIntegral>,
    /// The braid's total normal force N = Σ λ/h over the self-contact rows, averaged over the
    /// settle's last second ([`Settled::contact_normal_force_dyn`]; dyn). Coulomb's law
    /// bounds the tension friction can hold across the braid by μN, reached where every
    /// contact slides along the strands.
    pub contact_normal_force_dyn: f64,
}

/// The first integral H = Bκ²/2 + Cτ²/2 + n·t over the joints of a settled knot's loop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopFirstIntegral {
    /// Its mean over the loop's joints (dyn).
    pub mean_dyn: f64,
    /// (max − min)/mean over them. H is one number along a settled loop, so this is the
    /// chain's discretisation: 0.3–11 % in `cargo xtask audoly`'s runs (less on finer
    /// chains), as the frictionless check's H/T outside the braid (2.3 % at h/R = 0.009 on
    /// 400 bodies).
    pub spread: f64,
    /// The loop's joints it is taken over.
    pub joints: usize,
}

impl LoopFirstIntegral {
    /// The loop radius R = √(B/(2H)) that H gives (cm): where the loop's tangent is ⊥ the pull,
    /// n·t → 0 at leading order in h/R and Bκ²/2 → H, as `T R²/B = 1/2` has it without
    /// friction (where H = T).
    pub fn loop_radius_cm(&self, bending_stiffness_dyn_cm2: f64) -> f64 {
        (bending_stiffness_dyn_cm2 / (2.0 * self.mean_dyn)).sqrt()
    }
}

impl LooseKnot {
    /// The loop radius R: the mean of [`LooseKnot::loop_radii_cm`] (cm; NaN if none).
    pub fn loop_radius_cm(&self) -> f64 {
        self.loop_radii_cm.iter().sum::<f64>() / self.loop_radii_cm.len() as f64
    }

    /// `T R²/B` with R a loop radius (→ 1/2).
    pub fn tension_number(&self, radius_cm: f64) -> f64 {
        self.tension_dyn * radius_cm * radius_cm / self.bending_stiffness_dyn_cm2
    }

    /// The largest `|H_j/T − 1|` over the joints `select` picks (by index).
    pub fn worst_first_integral(&self, select: impl Fn(usize) -> bool) -> f64 {
        let deviations = self.first_integral.iter().enumerate().filter(|(j, _)| select(*j));
        deviations.map(|(_, h)| (h / self.tension_dyn - 1.0).abs()).fold(0.0, f64::max)
    }
}

/// A change of the shipped loose-trefoil set-up, for the refinements.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Refinement {
    /// Bodies of the rod, instead of the rod file's.
    pub bodies: Option<usize>,
    /// The rod's radius h (cm), instead of the rod file's.
    pub rod_radius_cm: Option<f64>,
    /// The time step (s), instead of the scenario's (a thinner rod needs a smaller one: a
    /// strand must not pass through another within one step).
    pub time_step_s: Option<f64>,
}

/// The loose-trefoil scenario with the pull `tension_dyn`, changed by `refinement`.
pub fn scenario(
    root: &Path,
    tension_dyn: f64,
    refinement: Refinement,
) -> Result<LoadedScenario, ValidationError> {
    let mut loaded = LoadedScenario::load(root.join(SCENARIO))?;
    if let Body::Rod(rod) = &mut loaded.body {
        rod.body_count = refinement.bodies.unwrap_or(rod.body_count);
        rod.radius_cm = refinement.rod_radius_cm.unwrap_or(rod.radius_cm);
    }
    if let Some(h) = refinement.time_step_s {
        loaded.scenario.time_step_s = h;
    }
    if let Some(Phase::Load(load)) = loaded.scenario.phases.first_mut() {
        load.force_dyn = tension_dyn;
    }
    Ok(loaded)
}

/// The bending stiffness B of the loose trefoil's rod (dyn·cm²), as its file gives it.
pub fn bending_stiffness(root: &Path) -> Result<f64, ValidationError> {
    let loaded = LoadedScenario::load(root.join(SCENARIO))?;
    match &loaded.body {
        Body::Rod(rod) => Ok(rod.bending_stiffness_dyn_cm2),
        _ => Err(ValidationError::Scenario {
            path: loaded.path.clone(),
            reason: "its body is not a rod".into(),
        }),
    }
}

/// Settles the scenario at `tension_dyn`, changed by `refinement`, and measures it; an
/// error if the knot it settled into is not the one it started as (the step lets a thin
/// strand pass through another when it moves more than its diameter in one step).
pub fn run(
    root: &Path,
    tension_dyn: f64,
    refinement: Refinement,
) -> Result<LooseKnot, ValidationError> {
    run_loaded(&scenario(root, tension_dyn, refinement)?)
}

/// Settles `loaded` (the loose-trefoil scenario, changed as a study needs) and measures it,
/// with the check of [`run`] that the knot is still the one it started as; an error if no
/// point of the settled loop has its tangent ⊥ the pull outside the braid.
pub fn run_loaded(loaded: &LoadedScenario) -> Result<LooseKnot, ValidationError> {
    let knot = settle_and_measure(loaded)?;
    require_loop_radius(&knot, loaded)?;
    Ok(knot)
}

/// An error unless `knot` (settled from `loaded`) has a point of its loop whose tangent is ⊥
/// the pull outside the braid, where its loop radius is measured.
pub fn require_loop_radius(
    knot: &LooseKnot,
    loaded: &LoadedScenario,
) -> Result<(), ValidationError> {
    if knot.loop_radii_cm.is_empty() {
        return Err(ValidationError::Scenario {
            path: loaded.path.clone(),
            reason: "no point of the settled loop has its tangent perpendicular to the pull \
                     (is the knot still there?)"
                .into(),
        });
    }
    Ok(())
}

/// [`run_loaded`] without its demand for a point ⊥ the pull: the loop radii may be none (the
/// frictional study measures such a loop by its first integral).
pub fn settle_and_measure(loaded: &LoadedScenario) -> Result<LooseKnot, ValidationError> {
    settle_checked(loaded).map(|settled| measure(&settled))
}

/// Settles `loaded` (a loose knot started as an open torus knot), or an error if the knot it
/// settled into is not the one it started as (the step lets a thin strand pass through another
/// when it moves more than its diameter in one step).
pub fn settle_checked(loaded: &LoadedScenario) -> Result<Settled, ValidationError> {
    let Some(InitialShape::OpenTorusKnot(start)) = loaded.scenario.initial_shape else {
        return Err(ValidationError::Scenario {
            path: loaded.path.clone(),
            reason: "it has no initial knot (initial_shape)".into(),
        });
    };
    let settled = settle(loaded)?;
    let (expected, found) = (format!("{}_1", start.crossings), knot_type(&settled));
    if found != expected {
        return Err(ValidationError::KnotChanged { path: loaded.path.clone(), expected, found });
    }
    Ok(settled)
}

/// The knot type (Rolfsen name) of the settled rod's body centres.
fn knot_type(settled: &Settled) -> String {
    let data = &settled.world.data().tree;
    let centres: Vec<DVec3> =
        (0..settled.world.model().body_count()).map(|i| data.body_centre(i)).collect();
    analyse_knot(&centres, &KnotOptions::default())
        .map_or_else(|e| format!("? ({e})"), |report| report.knot.to_string())
}

/// The loop radii (none where no point ⊥ the pull lies outside the braid) and the first
/// integral of a settled loose knot.
pub fn measure(settled: &Settled) -> LooseKnot {
    let (world, rod) = (&settled.world, &settled.rod);
    let model = world.model();
    let data = world.data();
    let ell = rod.segment_length_cm();
    let (b, c, t) =
        (rod.bending_stiffness_dyn_cm2, rod.twist_stiffness_dyn_cm2, settled.load.force_dyn);
    // Arc length (from the head end) of the contact points and of joint j (jℓ).
    let contacts: Vec<f64> = data
        .self_contacts
        .iter()
        .flat_map(|contact| [contact.u_a, contact.u_b])
        .map(|u| (u + 0.5) * ell)
        .collect();
    let margin = (BRAID_MARGIN * rod.radius_cm).max(BRAID_MARGIN_SEGMENTS * ell);
    let outside = |s: f64| contacts.iter().all(|contact| (contact - s).abs() >= margin);
    let directions: Vec<DVec3> =
        data.tree.body_frames.iter().map(|frame| frame.rotation.col(0)).collect();
    let joints = model.joints();
    let bending: Vec<bool> =
        joints.iter().map(|joint| matches!(joint.kind, JointKind::UniversalYz)).collect();
    // Curvature at each bending joint: the turn between the bodies it joins over 2ℓ.
    let curvature = |j: usize| directions[j - 1].angle_between(directions[j]) / (2.0 * ell);
    let mut loop_radii_cm = Vec::new();
    for j in (1..directions.len()).filter(|&j| bending[j]) {
        let (before, after) = (directions[j - 1].x, directions[j].x);
        if before.signum() == after.signum() {
            continue;
        }
        // Tangents at the segments' midpoints, jℓ ∓ ℓ; the crossing between them.
        let fraction = before / (before - after);
        let s = (j as f64 - 1.0 + 2.0 * fraction) * ell;
        if !outside(s) {
            continue;
        }
        let neighbour = if fraction < 0.5 { j.checked_sub(2) } else { Some(j + 2) };
        let kappa = match neighbour.filter(|&k| k >= 1 && k < directions.len() && bending[k]) {
            Some(k) => {
                let weight = ((s - j as f64 * ell) / (2.0 * ell)).abs();
                (1.0 - weight) * curvature(j) + weight * curvature(k)
            }
            None => curvature(j),
        };
        loop_radii_cm.push(1.0 / kappa);
    }
    let first_integral: Vec<f64> = data
        .internal
        .loads
        .iter()
        .map(|load| {
            let bend = load.bending_dyn_cm();
            bend * bend / (2.0 * b) + load.twist_dyn_cm.powi(2) / (2.0 * c) + load.tension_dyn
        })
        .collect();
    let outside_braid = (0..joints.len()).map(|j| outside(j as f64 * ell)).collect();
    let on_loop = loop_stretch(&contacts).map(|(from, to)| {
        move |j: usize| (from + margin..=to - margin).contains(&(j as f64 * ell))
    });
    let loop_first_integral = on_loop.and_then(|on_loop| {
        let values: Vec<f64> =
            (0..joints.len()).filter(|&j| on_loop(j)).map(|j| first_integral[j]).collect();
        if values.is_empty() {
            return None;
        }
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let low = values.iter().copied().fold(f64::INFINITY, f64::min);
        let high = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Some(LoopFirstIntegral {
            mean_dyn: mean,
            spread: (high - low) / mean,
            joints: values.len(),
        })
    });
    LooseKnot {
        tension_dyn: t,
        bending_stiffness_dyn_cm2: b,
        rod_radius_cm: rod.radius_cm,
        loop_radii_cm,
        first_integral,
        outside_braid,
        bending_joint: bending,
        loop_first_integral,
        contact_normal_force_dyn: settled.contact_normal_force_dyn,
    }
}

/// The loop among the contacts at arc lengths `contacts` (cm, in any order): the longest
/// stretch between two of them that holds none, as (from, to); `None` with fewer than two.
fn loop_stretch(contacts: &[f64]) -> Option<(f64, f64)> {
    let mut sorted = contacts.to_vec();
    sorted.sort_by(f64::total_cmp);
    let gaps = sorted.windows(2).map(|pair| (pair[0], pair[1]));
    gaps.max_by(|a, b| (a.1 - a.0).total_cmp(&(b.1 - b.0)))
}

/// The pulls of the study (dyn): 5 to 50, spanning 10×, so R spans √10.
pub const TENSIONS_DYN: [f64; 4] = [5.0, 10.0, 20.0, 50.0];

/// The pull of the refinement (dyn).
pub const REFINED_TENSION_DYN: f64 = 10.0;

/// The refinement in h/R at a fixed resolution of the braid (body length ℓ = 7.5 h): the
/// rod's radius halved twice with twice the bodies each time (and the time step halved
/// with it), from the coarse set-up to the fine one; the shipped rod (h = 0.02 cm, 400 bodies)
/// is the middle one.
pub const REFINEMENTS: [Refinement; 2] = [
    Refinement { bodies: Some(200), rod_radius_cm: Some(0.04), time_step_s: Some(0.02) },
    Refinement { bodies: Some(800), rod_radius_cm: Some(0.01), time_step_s: Some(0.01) },
];

/// Every run of the loose-trefoil study, settled and measured.
#[derive(Clone, Debug, PartialEq)]
pub struct LooseKnotStudy {
    /// The shipped set-up at each of [`TENSIONS_DYN`].
    pub tensions: Vec<LooseKnot>,
    /// At [`REFINED_TENSION_DYN`], h/R falling: the coarse refinement, the shipped set-up,
    /// the fine refinement.
    pub refinement: Vec<LooseKnot>,
}

/// Runs the study, each run in its own thread.
pub fn study(root: &Path) -> Result<LooseKnotStudy, ValidationError> {
    let cases: Vec<(f64, Refinement)> = TENSIONS_DYN
        .iter()
        .map(|&t| (t, Refinement::default()))
        .chain(REFINEMENTS.iter().map(|&r| (REFINED_TENSION_DYN, r)))
        .collect();
    let mut knots = std::thread::scope(|scope| {
        let runs: Vec<_> =
            cases.iter().map(|&(t, r)| scope.spawn(move || run(root, t, r))).collect();
        runs.into_iter().map(|r| r.join().expect("a validation run panicked")).collect::<Vec<_>>()
    })
    .into_iter()
    .collect::<Result<Vec<LooseKnot>, _>>()?;
    let fine = knots.pop().expect("the fine refinement");
    let coarse = knots.pop().expect("the coarse refinement");
    let shipped = knots
        .iter()
        .find(|k| k.tension_dyn == REFINED_TENSION_DYN)
        .expect("the refined tension is one of the study's")
        .clone();
    Ok(LooseKnotStudy { tensions: knots, refinement: vec![coarse, shipped, fine] })
}

impl LooseKnotStudy {
    /// The rows of the table: `T R²/B` at each tension, the slope of log R against log T,
    /// `T R²/B` and the first integral outside the braid along the refinement.
    pub fn checks(&self) -> Vec<Check> {
        let mut checks = Vec::new();
        for knot in &self.tensions {
            checks.push(tension_number_check("loose trefoil", knot));
        }
        let (first, last) = (&self.tensions[0], &self.tensions[self.tensions.len() - 1]);
        let slope = (last.loop_radius_cm() / first.loop_radius_cm()).ln()
            / (last.tension_dyn / first.tension_dyn).ln();
        checks.push(Check {
            name: "loose trefoil: slope of log R against log T".into(),
            setup: format!("T = {} … {} dyn", first.tension_dyn, last.tension_dyn),
            formula: "R ∝ T^(−1/2)",
            source: "Audoly, Clauvelin & Neukirch (2007)",
            expected: -0.5,
            measured: slope,
            unit: "",
            tolerance: 0.02,
        });
        for knot in &self.refinement {
            checks.push(tension_number_check("loose trefoil, refined", knot));
        }
        for knot in &self.refinement {
            checks.push(Check {
                name: "loose trefoil: first integral H/T outside the braid".into(),
                setup: format!(
                    "T = {} dyn, h/R = {:.4}, {} bodies; joints ≥ max({BRAID_MARGIN} h, \
                     {BRAID_MARGIN_SEGMENTS} ℓ) of arc from every contact",
                    knot.tension_dyn,
                    knot.rod_radius_cm / knot.loop_radius_cm(),
                    knot.first_integral.len()
                ),
                formula: "H = Bκ²/2 + Cτ²/2 + n·t = T",
                source: "Kirchhoff rod with frictionless contact (Audoly et al. 2007)",
                expected: 1.0,
                measured: 1.0 + knot.worst_first_integral(|j| knot.outside_braid[j]),
                unit: "",
                tolerance: 0.1,
            });
        }
        checks
    }
}

/// The `T R²/B` row of one run.
fn tension_number_check(name: &str, knot: &LooseKnot) -> Check {
    let r = knot.loop_radius_cm();
    let radii: Vec<String> = knot.loop_radii_cm.iter().map(|r| format!("{r:.4}")).collect();
    Check {
        name: format!("{name}, T = {} dyn: T R²/B", knot.tension_dyn),
        setup: format!(
            "R = {r:.4} cm (at the ⊥ points: {}), h/R = {:.4}, {} bodies, settled 40 s",
            radii.join(", "),
            knot.rod_radius_cm / r,
            knot.first_integral.len()
        ),
        formula: "T R²/B → 1/2 (R: radius of curvature where t ⊥ T)",
        source: "Audoly, Clauvelin & Neukirch, PRL 99, 164301 (2007)",
        expected: 0.5,
        measured: knot.tension_number(r),
        unit: "",
        tolerance: 0.1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_loop_is_the_longest_stretch_without_a_contact() {
        // A braid's contacts at 10–12 cm and 30–31 cm of arc (either strand, in any order):
        // the loop runs from 12 to 30 cm.
        let contacts = [30.5, 10.0, 12.0, 11.0, 31.0, 30.0];
        assert_eq!(loop_stretch(&contacts), Some((12.0, 30.0)));
        assert_eq!(loop_stretch(&[4.0]), None);
        assert_eq!(loop_stretch(&[]), None);
    }

    #[test]
    fn the_loop_radius_of_a_first_integral_holds_audolys_half() {
        // H R²/B = 1/2: B = 100 dyn·cm², H = 12.5 dyn → R = 2 cm.
        let integral = LoopFirstIntegral { mean_dyn: 12.5, spread: 0.0, joints: 10 };
        let radius = integral.loop_radius_cm(100.0);
        assert!((radius - 2.0).abs() < 1e-15, "{radius}");
        assert!((12.5 * radius * radius / 100.0 - 0.5).abs() < 1e-15);
    }
}
