//! # hagfish-validation
//!
//! The simulator against published elastic-rod theory (`docs/validation.md`): each check
//! runs a scenario of `data/validation/` on a rod of `data/rods/`, measures one number and
//! compares it with a formula that no one here wrote. `cargo xtask validate` prints the
//! table; the tests of this crate assert each check's tolerance.
//!
//! - [`cantilever`]: small tip load (Euler–Bernoulli `PL³/3B`), the internal bending moment
//!   against statics, and a large tip load against the elastica ([`elastica_tip`]).
//! - [`tension`]: a straight rod pulled at the tail: the axial force at every joint.
//! - [`clamped_buckling`]: a rod clamped at both ends, one end gripped and pushed: Euler's
//!   load `4π²B/L²`.
//! - [`loose_knot`]: a loose trefoil in a thin rod under tension: the loop radius
//!   (`T R²/B → 1/2`) and the first integral of the Kirchhoff equations.
//!
//! The reference solutions are plain functions: the elastica of a cantilever under a tip
//! load, which for a small load `α = PL²/B` deflects the tip by `αL/3` (Euler–Bernoulli):
//!
//! ```
//! let (x, y) = hagfish_validation::elastica_tip(0.03);
//! assert!((y - 0.01).abs() < 1e-5 && x < 1.0, "tip at ({x}, {y}) L");
//! let (_, large) = hagfish_validation::elastica_tip(3.0);
//! assert!(large < 1.0, "a large load deflects less than the linear α/3 = {large}");
//! ```

pub mod cantilever;
mod check;
pub mod clamped_buckling;
mod elastica;
mod error;
pub mod frictional_knot;
pub mod knot_loop;
pub mod loose_knot;
pub mod overhand_pull;
mod settle;
pub mod tension;

pub use check::Check;
pub use elastica::elastica_tip;
pub use error::ValidationError;
pub use settle::{Settled, settle};

/// Every check of the table at its default resolution, in the order of `docs/validation.md`.
pub fn all_checks(root: &std::path::Path) -> Result<Vec<Check>, ValidationError> {
    let mut checks = Vec::new();
    for bodies in [20, 50, 100] {
        checks.extend(cantilever::small_load(root, bodies)?);
    }
    checks.push(cantilever::large_load(root, 3.0)?);
    checks.push(tension::axial(root)?);
    checks.push(clamped_buckling::run(root, 100)?.check());
    checks.extend(loose_knot::study(root)?.checks());
    Ok(checks)
}
