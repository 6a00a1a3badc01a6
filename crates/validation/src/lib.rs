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
//! - [`loose_knot`]: a loose trefoil in a thin rod under tension: the loop radius
//!   (`T R²/B → 1/2`) and the first integral of the Kirchhoff equations.

pub mod cantilever;
mod check;
mod elastica;
mod error;
pub mod loose_knot;
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
    checks.extend(loose_knot::study(root)?.checks());
    Ok(checks)
}
