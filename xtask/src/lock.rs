//! `cargo xtask lock`: Audoly et al.'s loosening lock on the loose trefoil with friction
//! (`hagfish_validation::frictional_knot::release`): for each μ the knot is tightened by
//! 100 dyn, let go (F = 0) and settled; prints, as Markdown, a row per μ with the knot as let
//! go (with its friction number on the tightening branch at 100 dyn) and as settled, how far
//! its loop opened, σ' = ε/(2μ) of a knot that opened, the settled braid's normal force N as
//! N h²/(Bε³) (the σ' that Coulomb's μN would give where every contact slides: Audoly's σ at
//! leading order), and Audoly's lock ε₀/(2σ) with σ = 0.492 (docs/validation.md, "The
//! loosening lock").

use std::fmt::Write as _;
use std::path::Path;

use hagfish_sim::rows::Friction;
use hagfish_validation::frictional_knot::{self, Release};
use hagfish_validation::loose_knot::Refinement;

use crate::family::in_parallel;

/// A loop that opens by more than this fraction when let go is not locked (a locked loop
/// gives 1.0–1.2 % elastically as the pull goes).
const OPENED: f64 = 0.02;

/// What to run.
pub struct Request<'a> {
    /// The friction coefficients μ.
    pub coefficients: &'a [f64],
    /// Edges of the friction pyramid.
    pub edges: usize,
    /// The rod's bodies and the time step, where not the shipped ones.
    pub refinement: Refinement,
    /// Runs at a time.
    pub jobs: usize,
}

/// Runs every μ and prints the table.
pub fn run(root: &Path, request: &Request<'_>) -> Result<(), String> {
    let releases = in_parallel(request.coefficients, request.jobs, |&mu| {
        frictional_knot::release(root, Friction::pyramid(mu, request.edges), request.refinement)
    })?;
    let releases: Vec<Release> =
        releases.into_iter().collect::<Result<_, _>>().map_err(|e| e.to_string())?;
    println!("{}", table(&releases));
    Ok(())
}

/// The Markdown table of `releases`.
fn table(releases: &[Release]) -> String {
    let mut out = String::from(
        "| μ | let go: R (cm), ε₀ | its friction number at 100 dyn | settled: R (cm), ε | opened | \
         σ' = ε/(2μ) if opened | settled braid's N h²/(Bε³) | Audoly's lock ε₀/(2σ), σ = 0.492 |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for release in releases {
        let (let_go, settled) = (release.let_go_loop(), release.settled_loop());
        let coefficient = release.let_go.coefficient;
        let sigma = if release.opening() > OPENED {
            format!("{:.3}", settled.epsilon / (2.0 * coefficient))
        } else {
            "locked".to_owned()
        };
        let _ = writeln!(
            out,
            "| {} | {:.4}, {:.4} | {:+.3} | {:.4}, {:.4} | {:.1} % | {sigma} | {:.3} | {:.4} |",
            coefficient,
            let_go.loop_radius_cm,
            let_go.epsilon,
            let_go.friction_number,
            settled.loop_radius_cm,
            settled.epsilon,
            100.0 * release.opening(),
            frictional_knot::SIGMA * settled.normal_force_number,
            release.lock_coefficient(),
        );
    }
    out
}
