//! The loose trefoil with friction (Audoly, Clauvelin & Neukirch, PRL 99, 164301, 2007; as
//! restated by Choi, Tong, Jawed & Joo, J. Appl. Mech. 88:051010, 2021): a knot pulled by F
//! holds its loop where F h²/B = ε⁴/2 ± μσε³, ε = √(h/R), σ = 0.492, + on the tightening
//! branch (the pull must overcome friction to close the loop) and − on the loosening one.
//!
//! Set-up: the shipped loose trefoil (`data/validation/loose_trefoil.ron`) with friction.
//! - Tightening: pulled at T, ramped over 1 s from the torus start. While the pull ramps
//!   the loop opens past the branch; it then closes until friction holds it (approached
//!   from the loose side: on the tightening branch).
//! - Loosening: first pulled at [`TIGHT_PULL_DYN`] (ramped over 10 s and held), then at T
//!   at once: the loop opens until friction holds it.
//!
//! Each is settled (the final pull held [`FINAL_PULL_S`]) and its loop radius R measured as
//! the frictionless check measures it (`loose_knot.rs`); the friction term F h²/B − ε⁴/2 is
//! reported over μσε³, the **friction number**: +1 on Audoly's tightening branch, −1 on the
//! loosening one.

use std::path::Path;

use hagfish_control::Phase;
use hagfish_sim::rows::Friction;

use crate::error::ValidationError;
use crate::loose_knot::{self, Refinement};

/// Audoly et al.'s braid coefficient σ of the trefoil.
pub const SIGMA: f64 = 0.492;

/// How long the final pull is held (s). A loop closing onto the tightening branch at
/// μ = 0.02 and 20 dyn is still closing after the scenario's 40 s (friction number 1.363,
/// 1.158 after 120 s and after 240 s); at μ = 0.05 and on the loosening branch 40 s are within
/// 1 % of 240 s.
pub const FINAL_PULL_S: f64 = 120.0;

/// The pull that tightens the knot before a loosening run (dyn): its frictionless loop
/// radius, 0.71 cm, is well inside the loosening branch at the study's pulls.
pub const TIGHT_PULL_DYN: f64 = 100.0;

/// How the knot reached its pull.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Branch {
    /// Closed onto the pull from a looser loop.
    Tightening,
    /// Opened onto the pull from a tighter loop.
    Loosening,
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
    /// The loop radius R (cm).
    pub loop_radius_cm: f64,
    /// ε = √(h/R).
    pub epsilon: f64,
    /// (F h²/B − ε⁴/2) / (μσε³): Audoly's ±1.
    pub friction_number: f64,
}

/// Settles the loose trefoil (changed by `refinement`) with `friction` on `branch` at the
/// final pull `tension_dyn`, and measures it.
pub fn run(
    root: &Path,
    (branch, tension_dyn): (Branch, f64),
    friction: Friction,
    refinement: Refinement,
) -> Result<FrictionalKnot, ValidationError> {
    let coefficient = friction.coefficient;
    let first_pull = match branch {
        Branch::Tightening => tension_dyn,
        Branch::Loosening => TIGHT_PULL_DYN,
    };
    let mut loaded = loose_knot::scenario(root, first_pull, refinement)?;
    loaded.scenario.friction = Some(friction);
    let Some(Phase::Load(first)) = loaded.scenario.phases.first_mut() else {
        return Err(ValidationError::Scenario {
            path: loaded.path.clone(),
            reason: "its first phase is not a load".into(),
        });
    };
    // The final pull is held FINAL_PULL_S (the scenario holds its pull 40 s).
    let mut last = first.clone();
    last.until.seconds = FINAL_PULL_S;
    match branch {
        Branch::Tightening => {
            loaded.scenario.duration_s += FINAL_PULL_S - first.until.seconds;
            *first = last;
        }
        Branch::Loosening => {
            first.ramp_s = 10.0;
            (last.force_dyn, last.ramp_s) = (tension_dyn, 0.0);
            loaded.scenario.duration_s += FINAL_PULL_S;
            loaded.scenario.phases.push(Phase::Load(last));
        }
    }
    let knot = loose_knot::run_loaded(&loaded)?;
    let (h, b) = (knot.rod_radius_cm, knot.bending_stiffness_dyn_cm2);
    let r = knot.loop_radius_cm();
    let epsilon = (h / r).sqrt();
    let term = tension_dyn * h * h / b - epsilon.powi(4) / 2.0;
    Ok(FrictionalKnot {
        branch,
        tension_dyn,
        coefficient,
        loop_radius_cm: r,
        epsilon,
        friction_number: term / (coefficient * SIGMA * epsilon.powi(3)),
    })
}
