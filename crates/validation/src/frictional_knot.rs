//! The loose trefoil with friction (Audoly, Clauvelin & Neukirch, PRL 99, 164301, 2007; as
//! restated by Choi, Tong, Jawed & Joo, J. Appl. Mech. 88:051010, 2021): a knot pulled by F
//! holds its loop where F h²/B = ε⁴/2 ± μσε³, ε = √(h/R), σ = 0.492, + on the tightening
//! branch (the pull must overcome friction to close the loop) and − on the loosening one.
//!
//! Set-up: the shipped loose trefoil (`data/validation/loose_trefoil.ron`) with friction.
//! - Tightening: pulled at T, ramped from the torus start (over [`TIGHTENING_RAMP_S`] in the
//!   shipped study: while the pull ramps the loop opens past the branch; it then closes until
//!   friction holds it, approached from the loose side). How the loop gets there matters: a
//!   slower ramp closes it quasi-statically onto a larger friction number at ε ≥ 0.1
//!   (`cargo xtask audoly --ramp`, docs/validation.md).
//! - Loosening: first pulled tighter (by [`TIGHT_PULL_DYN`] in the shipped study; ramped over
//!   10 s and held), then at T at once: the loop opens until friction holds it.
//!
//! Each is settled (the final pull held [`FINAL_PULL_S`]) and its loop radius R measured two
//! ways (`loose_knot.rs`): as the frictionless check measures it, from the curvature where the
//! loop's tangent is ⊥ the pull, and from the loop's first integral H, R = √(B/(2H)) (the
//! same at leading order in h/R; the second needs no point ⊥ the pull, which a thick rod's
//! loop may not have outside its braid). For each the friction term F h²/B − ε⁴/2 is reported
//! over μσε³, the **friction number**: +1 on Audoly's tightening branch, −1 on the loosening
//! one.

use std::path::Path;

use hagfish_control::Phase;
use hagfish_sim::rows::Friction;

use crate::error::ValidationError;
use hagfish_scenario::LoadedScenario;

use crate::loose_knot::{self, LooseKnot, Refinement};
use crate::settle::Settled;

/// Audoly et al.'s braid coefficient σ of the trefoil.
pub const SIGMA: f64 = 0.492;

/// How long the final pull is held (s). A loop closing onto the tightening branch at
/// μ = 0.02 and 20 dyn is still closing after the scenario's 40 s (friction number 1.363,
/// 1.157 after 120 s, 1.158 after 240 s); at μ = 0.05 and on the loosening branch 40 s are within
/// 1 % of 240 s.
pub const FINAL_PULL_S: f64 = 120.0;

/// The pull that tightens the knot before a loosening run (dyn): its frictionless loop
/// radius, 0.71 cm, is well inside the loosening branch at the study's pulls.
pub const TIGHT_PULL_DYN: f64 = 100.0;

/// The shipped study's tightening ramp (s): the pull rises from 0 to T over it, from the
/// torus start.
pub const TIGHTENING_RAMP_S: f64 = 1.0;

/// How long the first pull of a loosening run (and of [`release`]) ramps (s).
pub const LOOSENING_FIRST_RAMP_S: f64 = 10.0;

/// How the knot reached its pull.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Branch {
    /// Closed onto the pull from a looser loop: the pull ramped from 0 over `ramp_s`, then
    /// held; the final pull's [`FINAL_PULL_S`] include the ramp.
    Tightening {
        /// The ramp (s; [`TIGHTENING_RAMP_S`] in the shipped study).
        ramp_s: f64,
        /// Where the ramp starts: `None` from the torus start (the shipped study), or the
        /// loop a first pull of this many dyn holds (ramped over [`LOOSENING_FIRST_RAMP_S`],
        /// held to the scenario's 40 s), looser than the final pull's where friction stops
        /// a loop opening from the torus short of it.
        from_dyn: Option<f64>,
    },
    /// Opened onto the pull from a tighter loop: the one a pull of `from_dyn` holds (ramped
    /// over [`LOOSENING_FIRST_RAMP_S`], held to the scenario's 40 s).
    Loosening {
        /// The pull that tightened it first (dyn; [`TIGHT_PULL_DYN`] in the shipped study).
        from_dyn: f64,
    },
}

/// One settled frictional knot.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionalKnot {
    /// How it got there.
    pub branch: Branch,
    /// The final pull F (dyn).
    pub tension_dyn: f64,
    /// μ.
    pub coefficient: f64,
    /// The loop measured where its tangent is ⊥ the pull; `None` where no such point lies
    /// outside the braid.
    pub perpendicular: Option<LoopMeasure>,
    /// The loop measured by its first integral H; `None` where the loop has no joint outside
    /// the braid.
    pub first_integral: Option<LoopMeasure>,
    /// (max − min)/mean of H over the loop's joints, the chain's discretisation
    /// ([`loose_knot::LoopFirstIntegral::spread`]); `None` with `first_integral`.
    pub first_integral_spread: Option<f64>,
    /// The rod's radius h (cm).
    pub rod_radius_cm: f64,
    /// The rod's bending stiffness B (dyn·cm²).
    pub bending_stiffness_dyn_cm2: f64,
}

/// One measure of a settled frictional loop: its radius R, ε = √(h/R) and the friction number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopMeasure {
    /// The loop radius R (cm).
    pub loop_radius_cm: f64,
    /// ε = √(h/R).
    pub epsilon: f64,
    /// (F h²/B − ε⁴/2) / (μσε³): Audoly's ±1.
    pub friction_number: f64,
    /// N h²/(σBε³), N the braid's total normal force
    /// ([`LooseKnot::contact_normal_force_dyn`](loose_knot::LooseKnot::contact_normal_force_dyn)):
    /// the friction number Coulomb's law gives where every contact slides along the strands,
    /// μN over μσBε³/h² (the friction number's bound: the law's |F − H| ≤ μN across the
    /// braid). Audoly's σ is this number's 1 at leading order in ε.
    pub normal_force_number: f64,
}

/// The frictionless control of a frictional knot: the same rod without friction, pulled at
/// F₀ = B/(2R²), the pull Audoly et al.'s leading term gives for the frictional knot's loop
/// radius R, ramped over [`TIGHTENING_RAMP_S`] and held [`FINAL_PULL_S`] as the frictional
/// runs are (the frictionless check's 40 s do not settle the thick rods of ε ≥ 0.2: at
/// h = 0.08 cm a loop of 2.24 cm was 2.42 cm at 40 s). Its c = F₀R₀²/B (R₀ its own loop
/// radius, ≈ R) is the model's coefficient of ε⁴ where the law has ½: what the pull would be
/// at that loop without friction.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionlessControl {
    /// The pull F₀ (dyn).
    pub tension_dyn: f64,
    /// The loop radius R₀ it settles at (cm).
    pub loop_radius_cm: f64,
    /// c = F₀R₀²/B (Audoly's ½).
    pub tension_number: f64,
    /// Its braid's normal force N₀ h²/(σBε₀³), ε₀ = √(h/R₀)
    /// ([`LoopMeasure::normal_force_number`]): the frictionless braid's.
    pub normal_force_number: f64,
}

/// Settles the loose trefoil (changed by `refinement`) with `friction` on `branch` at the
/// final pull `tension_dyn`, and measures it.
pub fn run(
    root: &Path,
    (branch, tension_dyn): (Branch, f64),
    friction: Friction,
    refinement: Refinement,
) -> Result<FrictionalKnot, ValidationError> {
    let loaded = scenario(root, (branch, tension_dyn), Some(friction), refinement)?;
    let knot = loose_knot::settle_and_measure(&loaded)?;
    let frictional = FrictionalKnot::of(&knot, (branch, tension_dyn), friction.coefficient);
    if frictional.perpendicular.is_none() && frictional.first_integral.is_none() {
        return Err(ValidationError::Scenario {
            path: loaded.path.clone(),
            reason: "the settled loop has no joint outside its braid to measure".into(),
        });
    }
    Ok(frictional)
}

/// The loose trefoil with `friction` (`None`: frictionless), set up to settle on `branch` at
/// the final pull `tension_dyn` (the module's set-up).
fn scenario(
    root: &Path,
    (branch, tension_dyn): (Branch, f64),
    friction: Option<Friction>,
    refinement: Refinement,
) -> Result<LoadedScenario, ValidationError> {
    let first_pull = match branch {
        Branch::Tightening { from_dyn: None, .. } => tension_dyn,
        Branch::Tightening { from_dyn: Some(from_dyn), .. } | Branch::Loosening { from_dyn } => {
            from_dyn
        }
    };
    let mut loaded = loose_knot::scenario(root, first_pull, refinement)?;
    loaded.scenario.friction = friction;
    let Some(Phase::Load(first)) = loaded.scenario.phases.first_mut() else {
        return Err(ValidationError::Scenario {
            path: loaded.path.clone(),
            reason: "its first phase is not a load".into(),
        });
    };
    // The final pull is held FINAL_PULL_S (the scenario holds its pull 40 s).
    let mut last = first.clone();
    last.until.seconds = FINAL_PULL_S;
    if let Branch::Tightening { ramp_s, from_dyn: None } = branch {
        // From the torus: the final pull alone, ramped.
        loaded.scenario.duration_s += FINAL_PULL_S - first.until.seconds;
        *first = last;
        first.ramp_s = ramp_s;
        return Ok(loaded);
    }
    // From the loop the first pull holds (to the scenario's 40 s): then the final pull.
    let final_ramp_s = match branch {
        Branch::Tightening { ramp_s, .. } => ramp_s,
        Branch::Loosening { .. } => 0.0,
    };
    first.ramp_s = LOOSENING_FIRST_RAMP_S;
    (last.force_dyn, last.ramp_s) = (tension_dyn, final_ramp_s);
    loaded.scenario.duration_s += FINAL_PULL_S;
    loaded.scenario.phases.push(Phase::Load(last));
    Ok(loaded)
}

/// The pull (dyn) that holds a loop at `epsilon` by Audoly et al.'s law on a rod of radius
/// `rod_radius_cm` and bending stiffness B, on the tightening (`Tightening`) or loosening
/// branch: F = (B/h²)(ε⁴/2 ± μσε³). Not positive where the loosening branch locks (μ ≥ ε/(2σ)).
pub fn audoly_pull(
    (rod_radius_cm, bending_stiffness_dyn_cm2): (f64, f64),
    epsilon: f64,
    coefficient: f64,
    branch: Branch,
) -> f64 {
    let sign = match branch {
        Branch::Tightening { .. } => 1.0,
        Branch::Loosening { .. } => -1.0,
    };
    let number = epsilon.powi(4) / 2.0 + sign * coefficient * SIGMA * epsilon.powi(3);
    bending_stiffness_dyn_cm2 / (rod_radius_cm * rod_radius_cm) * number
}

/// How much tighter (in ε) the loop a loosening [`AtEpsilon`] run starts from is than its
/// target: its first pull is the tightening branch's at 1.5 ε.
pub const LOOSENING_START: f64 = 1.5;

/// Where an [`AtEpsilon`] run's tightening ramp starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TighteningStart {
    /// From the torus start (the shipped study).
    #[default]
    Torus,
    /// From the loop the loosening branch holds at ε/[`LOOSENING_START`] (its pull, at least
    /// 0): looser than the target, where friction stops a loop opening from the torus short of
    /// it (μ ≥ 0.03 at ε = 0.05).
    Looser,
}

/// A run of Audoly et al.'s law at a target ε (`cargo xtask audoly`): the loose trefoil with
/// the rod's radius set to h = ε²R₀ for a loop radius R₀ (its B kept, so that every loop has as
/// many bodies), pulled at the law's F for ε on its branch with σ = 0.492.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AtEpsilon {
    /// μ.
    pub coefficient: f64,
    /// The target ε.
    pub target_epsilon: f64,
    /// h = ε²R₀ (cm).
    pub rod_radius_cm: f64,
    /// The branch and how the loop reaches it.
    pub branch: Branch,
    /// The law's F on that branch (dyn).
    pub tension_dyn: f64,
    /// Bodies and time step instead of the rod file's and the scenario's (a thin rod needs
    /// more of both: `cargo xtask audoly --bodies --time-step`); only these two of the
    /// refinement are read.
    pub resolution: Refinement,
}

impl AtEpsilon {
    /// The tightening run at `target_epsilon` (ramped over `ramp_s` from `start`) and the
    /// loosening one (from the tightening pull at [`LOOSENING_START`] ε), `None` where the
    /// loosening branch is at or below F = 0 (μ ≥ ε/(2σ): the knot locks);
    /// `bending_stiffness_dyn_cm2` is the rod's B ([`loose_knot::bending_stiffness`]).
    pub fn both_branches(
        (coefficient, target_epsilon): (f64, f64),
        loop_radius_cm: f64,
        bending_stiffness_dyn_cm2: f64,
        (ramp_s, start): (f64, TighteningStart),
    ) -> (Self, Option<Self>) {
        let rod_radius_cm = target_epsilon * target_epsilon * loop_radius_cm;
        let rod = (rod_radius_cm, bending_stiffness_dyn_cm2);
        let pull = |epsilon, branch| audoly_pull(rod, epsilon, coefficient, branch);
        let at = |branch| Self {
            coefficient,
            target_epsilon,
            rod_radius_cm,
            branch,
            tension_dyn: pull(target_epsilon, branch),
            resolution: Refinement::default(),
        };
        let from_torus = Branch::Tightening { ramp_s, from_dyn: None };
        let loosening =
            Branch::Loosening { from_dyn: pull(LOOSENING_START * target_epsilon, from_torus) };
        let tightening = match start {
            TighteningStart::Torus => from_torus,
            TighteningStart::Looser => {
                let looser = pull(target_epsilon / LOOSENING_START, loosening).max(0.0);
                Branch::Tightening { ramp_s, from_dyn: Some(looser) }
            }
        };
        (at(tightening), Some(at(loosening)).filter(|run| run.tension_dyn > 0.0))
    }

    /// Settles the run with a friction pyramid of `edges` edges and measures it.
    pub fn run(&self, root: &Path, edges: usize) -> Result<FrictionalKnot, ValidationError> {
        let friction = Friction::pyramid(self.coefficient, edges);
        run(root, (self.branch, self.tension_dyn), friction, self.refinement())
    }

    /// The rod of the run: the loose trefoil's with h = ε²R₀, at the run's resolution.
    pub fn refinement(&self) -> Refinement {
        Refinement { rod_radius_cm: Some(self.rod_radius_cm), ..self.resolution }
    }
}

impl FrictionalKnot {
    /// The measures of a settled `knot` that reached `tension_dyn` on `branch` with μ =
    /// `coefficient`.
    fn of(knot: &LooseKnot, (branch, tension_dyn): (Branch, f64), coefficient: f64) -> Self {
        let (h, b) = (knot.rod_radius_cm, knot.bending_stiffness_dyn_cm2);
        let measure = |r: f64| {
            let epsilon = (h / r).sqrt();
            let rod = (tension_dyn, h, b);
            let friction_number = friction_number_against(0.5, rod, (epsilon, coefficient));
            let normal_force_number =
                normal_force_number(knot.contact_normal_force_dyn, (h, b), epsilon);
            LoopMeasure { loop_radius_cm: r, epsilon, friction_number, normal_force_number }
        };
        let loop_integral = knot.loop_first_integral;
        FrictionalKnot {
            branch,
            tension_dyn,
            coefficient,
            perpendicular: (!knot.loop_radii_cm.is_empty()).then(|| measure(knot.loop_radius_cm())),
            first_integral: loop_integral.map(|integral| measure(integral.loop_radius_cm(b))),
            first_integral_spread: loop_integral.map(|integral| integral.spread),
            rod_radius_cm: h,
            bending_stiffness_dyn_cm2: b,
        }
    }

    /// The loop measured where its tangent is ⊥ the pull, or why there is none.
    ///
    /// # Errors
    /// [`ValidationError::Scenario`] where the settled loop has no point ⊥ the pull outside
    /// its braid.
    pub fn at_perpendicular(&self) -> Result<&LoopMeasure, ValidationError> {
        self.perpendicular.as_ref().ok_or_else(|| ValidationError::Scenario {
            path: loose_knot::SCENARIO.into(),
            reason: "no point of the settled loop has its tangent perpendicular to the pull".into(),
        })
    }

    /// The friction number against the frictionless `control` (its c for Audoly's ½), at the
    /// loop measured where its tangent is ⊥ the pull: the share of the pull that friction
    /// holds, with whatever the model's frictionless loop differs from the law by (its finite
    /// ε, its chain) taken out.
    ///
    /// # Errors
    /// Those of [`FrictionalKnot::at_perpendicular`].
    pub fn controlled_friction_number(
        &self,
        control: &FrictionlessControl,
    ) -> Result<f64, ValidationError> {
        let rod = (self.tension_dyn, self.rod_radius_cm, self.bending_stiffness_dyn_cm2);
        let epsilon = self.at_perpendicular()?.epsilon;
        Ok(friction_number_against(control.tension_number, rod, (epsilon, self.coefficient)))
    }

    /// Settles this knot's [`FrictionlessControl`] on the rod `refinement` gives (the one
    /// this knot was settled with), for the loop radius measured where its tangent is ⊥ the
    /// pull.
    ///
    /// # Errors
    /// Those of loading and settling the loose trefoil (`loose_knot.rs`), and of
    /// [`FrictionalKnot::at_perpendicular`].
    pub fn frictionless_control(
        &self,
        root: &Path,
        refinement: Refinement,
    ) -> Result<FrictionlessControl, ValidationError> {
        let radius = self.at_perpendicular()?.loop_radius_cm;
        let pull = self.bending_stiffness_dyn_cm2 / (2.0 * radius * radius);
        let (knot, _) = frictionless_settled(root, pull, refinement)?;
        let radius = knot.loop_radius_cm();
        let (h, b) = (self.rod_radius_cm, self.bending_stiffness_dyn_cm2);
        let epsilon = (h / radius).sqrt();
        Ok(FrictionlessControl {
            tension_dyn: pull,
            loop_radius_cm: radius,
            tension_number: knot.tension_number(radius),
            normal_force_number: normal_force_number(
                knot.contact_normal_force_dyn,
                (h, b),
                epsilon,
            ),
        })
    }
}

/// The frictionless loose trefoil (changed by `refinement`) settled at the pull `tension_dyn`
/// as a [`FrictionlessControl`] is (ramped over [`TIGHTENING_RAMP_S`] from the torus and held
/// [`FINAL_PULL_S`]), measured, with the settled world (for its centreline).
///
/// # Errors
/// Those of loading and settling the loose trefoil (`loose_knot.rs`), and where no point of
/// the settled loop has its tangent ⊥ the pull.
pub fn frictionless_settled(
    root: &Path,
    tension_dyn: f64,
    refinement: Refinement,
) -> Result<(LooseKnot, Settled), ValidationError> {
    let tightening = Branch::Tightening { ramp_s: TIGHTENING_RAMP_S, from_dyn: None };
    let loaded = scenario(root, (tightening, tension_dyn), None, refinement)?;
    let settled = loose_knot::settle_checked(&loaded)?;
    let knot = loose_knot::measure(&settled);
    loose_knot::require_loop_radius(&knot, &loaded)?;
    Ok((knot, settled))
}

/// N h²/(σBε³) for a braid's total normal force N on a rod of radius h and bending
/// stiffness B at ε ([`LoopMeasure::normal_force_number`]).
pub fn normal_force_number(normal_force_dyn: f64, (h, b): (f64, f64), epsilon: f64) -> f64 {
    normal_force_dyn * h * h / (SIGMA * b * epsilon.powi(3))
}

/// (F h²/B − c ε⁴)/(μσε³) for a pull F on a rod of radius h and bending stiffness B at ε and
/// μ: the friction number with the law's leading ½ replaced by `c`.
fn friction_number_against(
    c: f64,
    (tension_dyn, h, b): (f64, f64, f64),
    (epsilon, coefficient): (f64, f64),
) -> f64 {
    let term = tension_dyn * h * h / b - c * epsilon.powi(4);
    term / (coefficient * SIGMA * epsilon.powi(3))
}

/// A knot tightened and then let go (F = 0): Audoly et al.'s loosening lock. On the loosening
/// branch at F = 0, ε⁴/2 = μσε³, so a knot let go at ε₀ opens until ε = 2μσ, and not at all
/// where μ ≥ ε₀/(2σ).
#[derive(Clone, Debug, PartialEq)]
pub struct Release {
    /// The knot when let go: tightened by [`TIGHT_PULL_DYN`] from the torus start (ramped over
    /// 10 s, held to the scenario's 40 s), on the tightening branch.
    pub let_go: FrictionalKnot,
    /// The same knot [`FINAL_PULL_S`] after it was let go (its friction number is
    /// −ε/(2μσ): −1 where it opened onto Audoly's loosening branch).
    pub settled: FrictionalKnot,
}

impl Release {
    /// How far the loop opened: R_settled / R_let_go − 1 (at the points ⊥ the pull).
    pub fn opening(&self) -> f64 {
        self.settled_loop().loop_radius_cm / self.let_go_loop().loop_radius_cm - 1.0
    }

    /// Audoly's lock for the knot as let go: μ = ε₀/(2σ).
    pub fn lock_coefficient(&self) -> f64 {
        self.let_go_loop().epsilon / (2.0 * SIGMA)
    }

    /// The let-go loop at its points ⊥ the pull ([`release`] has made sure it has them).
    pub fn let_go_loop(&self) -> &LoopMeasure {
        self.let_go.perpendicular.as_ref().expect("release measures the loop at its ⊥ points")
    }

    /// The settled loop at its points ⊥ the pull ([`release`] has made sure it has them).
    pub fn settled_loop(&self) -> &LoopMeasure {
        self.settled.perpendicular.as_ref().expect("release measures the loop at its ⊥ points")
    }
}

/// Tightens the loose trefoil (changed by `refinement`) with `friction`, lets it go and
/// measures it when let go and settled after.
pub fn release(
    root: &Path,
    friction: Friction,
    refinement: Refinement,
) -> Result<Release, ValidationError> {
    let coefficient = friction.coefficient;
    let from_tight = Branch::Loosening { from_dyn: TIGHT_PULL_DYN };
    let closed = Branch::Tightening { ramp_s: LOOSENING_FIRST_RAMP_S, from_dyn: None };
    let mut loaded = scenario(root, (from_tight, 0.0), Some(friction), refinement)?;
    let settled = loose_knot::run_loaded(&loaded)?;
    // The same run up to the moment it lets go (the same steps, bit for bit).
    loaded.scenario.phases.pop();
    loaded.scenario.duration_s -= FINAL_PULL_S;
    let let_go = loose_knot::run_loaded(&loaded)?;
    Ok(Release {
        let_go: FrictionalKnot::of(&let_go, (closed, TIGHT_PULL_DYN), coefficient),
        settled: FrictionalKnot::of(&settled, (from_tight, 0.0), coefficient),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn audolys_pull_adds_friction_when_tightening_and_takes_it_off_when_loosening() {
        // ε = 0.2, μ = 0.1, h = 0.04 cm, B = 100: ε⁴/2 = 8·10⁻⁴, μσε³ = 3.936·10⁻⁴, B/h² = 62500.
        let rod = (0.04, 100.0);
        let tight = audoly_pull(rod, 0.2, 0.1, Branch::Tightening { ramp_s: 1.0, from_dyn: None });
        assert!((tight - 62_500.0 * (8e-4 + 3.936e-4)).abs() < 1e-9, "{tight}");
        let loose = audoly_pull(rod, 0.2, 0.1, Branch::Loosening { from_dyn: 0.0 });
        assert!((loose - 62_500.0 * (8e-4 - 3.936e-4)).abs() < 1e-9, "{loose}");
        // The lock: at μ = ε/(2σ) the loosening branch holds the loop with no pull.
        let at_lock =
            audoly_pull(rod, 0.2, 0.2 / (2.0 * SIGMA), Branch::Loosening { from_dyn: 0.0 });
        assert!(at_lock.abs() < 1e-12, "{at_lock}");
    }

    /// The loads of a run's scenario: (force, ramp, held until) per phase.
    fn loads(branch: Branch, tension_dyn: f64) -> Vec<(f64, f64, f64)> {
        let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
        let loaded = scenario(root, (branch, tension_dyn), None, Refinement::default())
            .expect("the loose trefoil loads");
        let phases = loaded.scenario.phases.iter();
        phases
            .map(|phase| match phase {
                Phase::Load(load) => (load.force_dyn, load.ramp_s, load.until.seconds),
                other => panic!("not a load: {other:?}"),
            })
            .collect()
    }

    #[test]
    fn each_branch_reaches_its_final_pull_from_its_side() {
        let torus = Branch::Tightening { ramp_s: 60.0, from_dyn: None };
        assert_eq!(loads(torus, 5.0), [(5.0, 60.0, FINAL_PULL_S)]);
        let looser = Branch::Tightening { ramp_s: 60.0, from_dyn: Some(0.5) };
        assert_eq!(
            loads(looser, 5.0),
            [(0.5, LOOSENING_FIRST_RAMP_S, 40.0), (5.0, 60.0, FINAL_PULL_S)]
        );
        let loosening = Branch::Loosening { from_dyn: 20.0 };
        assert_eq!(
            loads(loosening, 2.0),
            [(20.0, LOOSENING_FIRST_RAMP_S, 40.0), (2.0, 0.0, FINAL_PULL_S)]
        );
    }

    #[test]
    fn a_looser_start_is_the_loosening_law_at_a_smaller_epsilon_and_never_a_push() {
        let start = (60.0, TighteningStart::Looser);
        // ε = 0.05 on R₀ = 4 cm (h = 0.01 cm), B = 1: at μ = 0.03 the law at ε/1.5 is open.
        let (tightening, _) = AtEpsilon::both_branches((0.03, 0.05), 4.0, 1.0, start);
        let Branch::Tightening { from_dyn: Some(from), .. } = tightening.branch else {
            panic!("{:?}", tightening.branch)
        };
        let law = audoly_pull(
            (0.01, 1.0),
            0.05 / LOOSENING_START,
            0.03,
            Branch::Loosening { from_dyn: 0.0 },
        );
        assert!((from - law).abs() < 1e-12 * law, "{from} {law}");
        assert!(from > 0.0 && from < tightening.tension_dyn, "{from}");
        // At μ = 0.04 it is locked there (μ > ε/(3σ)): the start pulls with nothing.
        let (locked, _) = AtEpsilon::both_branches((0.04, 0.05), 4.0, 1.0, start);
        assert!(matches!(locked.branch, Branch::Tightening { from_dyn: Some(0.0), .. }));
    }

    #[test]
    fn a_control_at_audolys_half_leaves_the_friction_number_as_it_is() {
        // h = 0.08, B = 100, R = 2 (ε = 0.2), μ = 0.1, F = 20: F h²/B = 1.28·10⁻³.
        let knot = FrictionalKnot {
            branch: Branch::Tightening { ramp_s: 1.0, from_dyn: None },
            tension_dyn: 20.0,
            coefficient: 0.1,
            perpendicular: Some(LoopMeasure {
                loop_radius_cm: 2.0,
                epsilon: 0.2,
                friction_number: 0.0,
                normal_force_number: 0.0,
            }),
            first_integral: None,
            first_integral_spread: None,
            rod_radius_cm: 0.08,
            bending_stiffness_dyn_cm2: 100.0,
        };
        let control = |c| FrictionlessControl {
            tension_dyn: 12.5,
            loop_radius_cm: 2.0,
            tension_number: c,
            normal_force_number: 1.0,
        };
        let plain = (1.28e-3 - 8e-4) / (0.1 * SIGMA * 8e-3);
        let at_half = knot.controlled_friction_number(&control(0.5)).expect("a ⊥ measure");
        assert!((at_half - plain).abs() < 1e-12);
        // A frictionless loop 10 % stiffer than the law takes 0.1 ε⁴/2 off the friction's share.
        let stiffer = (1.28e-3 - 8.8e-4) / (0.1 * SIGMA * 8e-3);
        let controlled = knot.controlled_friction_number(&control(0.55)).expect("a ⊥ measure");
        assert!((controlled - stiffer).abs() < 1e-12, "{controlled} {stiffer}");
    }
}
