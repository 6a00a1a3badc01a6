//! `cargo xtask audoly`: Audoly et al.'s law for the loose trefoil with friction over a range
//! of ε (`hagfish_validation::frictional_knot::run`; docs/validation.md, "Loose trefoil with
//! friction"). F h²/B = ε⁴/2 ± μσε³ with ε = √(h/R): for each μ and target ε the rod's
//! radius is set to h = ε²R₀ (the loop radius R₀ kept, so that every loop has as many bodies),
//! and the knot settled on each branch at the pull the law gives there with σ = 0.492 (the
//! tightening pull ramped slowly enough to close the loop quasi-statically). Prints,
//! as Markdown, a row per run with the ε and the friction number (F h²/B − ε⁴/2)/(μσε³) it
//! settled at: Audoly's ±1.

use std::fmt::Write as _;
use std::path::Path;

use hagfish_validation::ValidationError;
use hagfish_validation::frictional_knot::{AtEpsilon, Branch, FrictionalKnot, SIGMA};
use hagfish_validation::loose_knot;

use crate::family::{comma_list, in_parallel};

/// What to run.
pub struct Request<'a> {
    /// The friction coefficients μ.
    pub coefficients: &'a [f64],
    /// The target ε = √(h/R₀).
    pub epsilons: &'a [f64],
    /// The loop radius R₀ the rod's radius is chosen for (cm).
    pub loop_radius_cm: f64,
    /// The tightening pull's ramp (s), within the final pull's 120 s.
    pub ramp_s: f64,
    /// Edges of the friction pyramid.
    pub edges: usize,
    /// Runs at a time.
    pub jobs: usize,
}

/// Every run of `request`, per μ and ε the tightening one and, unless the knot locks, the
/// loosening one.
fn cases(request: &Request<'_>, bending_stiffness_dyn_cm2: f64) -> Vec<AtEpsilon> {
    let pairs =
        request.coefficients.iter().flat_map(|&mu| request.epsilons.iter().map(move |&e| (mu, e)));
    pairs
        .flat_map(|case| {
            let (tightening, loosening) = AtEpsilon::both_branches(
                case,
                request.loop_radius_cm,
                bending_stiffness_dyn_cm2,
                request.ramp_s,
            );
            std::iter::once(tightening).chain(loosening)
        })
        .collect()
}

/// Runs every case and prints the table.
pub fn run(root: &Path, request: &Request<'_>) -> Result<(), String> {
    let cases = cases(request, loose_knot::bending_stiffness(root).map_err(|e| e.to_string())?);
    let knots = in_parallel(&cases, request.jobs, |case| case.run(root, request.edges))?;
    println!("{}", table(&cases, &knots));
    println!(
        "`cargo xtask audoly --mu {} --epsilon {} --loop-radius {} --ramp {} --edges {}`: the \
         loose trefoil (data/validation/loose_trefoil.ron, data/rods/loose.ron with h = ε²R₀)",
        comma_list(request.coefficients),
        comma_list(request.epsilons),
        request.loop_radius_cm,
        request.ramp_s,
        request.edges,
    );
    Ok(())
}

/// The Markdown table: a row per run (a run that failed, with why).
fn table(cases: &[AtEpsilon], knots: &[Result<FrictionalKnot, ValidationError>]) -> String {
    let mut out = String::from(
        "| μ | target ε | h (cm) | branch | F (dyn) | settled: R (cm), ε | friction number | \
         σ' = σ·|number| |\n|---|---|---|---|---|---|---|---|\n",
    );
    for (case, knot) in cases.iter().zip(knots) {
        let branch = match case.branch {
            Branch::Tightening { ramp_s } => format!("tightening, ramped over {ramp_s} s"),
            Branch::Loosening { from_dyn } => format!("loosening from {from_dyn:.1} dyn"),
        };
        let settled = match knot {
            Ok(knot) => format!(
                "{:.4}, {:.4} | {:+.3} | {:.3}",
                knot.loop_radius_cm,
                knot.epsilon,
                knot.friction_number,
                SIGMA * knot.friction_number.abs()
            ),
            Err(error) => format!("failed: {error} | — | —"),
        };
        let _ = writeln!(
            out,
            "| {} | {} | {:.4} | {branch} | {:.2} | {settled} |",
            case.coefficient, case.target_epsilon, case.rod_radius_cm, case.tension_dyn,
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_locked_loosening_branch_has_no_run() {
        // μ = 0.2 locks a knot at ε ≤ 2μσ = 0.197: only its tightening run.
        let request = Request {
            coefficients: &[0.2],
            epsilons: &[0.1, 0.3],
            loop_radius_cm: 2.0,
            ramp_s: 60.0,
            edges: 8,
            jobs: 1,
        };
        let cases = cases(&request, 100.0);
        let branches: Vec<_> = cases.iter().map(|c| (c.target_epsilon, c.branch)).collect();
        assert_eq!(branches.len(), 3, "{branches:?}");
        assert!(matches!(branches[0], (0.1, Branch::Tightening { .. })));
        assert!(matches!(branches[2], (0.3, Branch::Loosening { .. })));
        assert!((cases[1].rod_radius_cm - 0.18).abs() < 1e-12);
    }
}
