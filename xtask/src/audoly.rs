//! `cargo xtask audoly`: Audoly et al.'s law for the loose trefoil with friction over a range
//! of ε (`hagfish_validation::frictional_knot::run`; docs/validation.md, "Loose trefoil with
//! friction"). F h²/B = ε⁴/2 ± μσε³ with ε = √(h/R): for each μ and target ε the rod's
//! radius is set to h = ε²R₀ (the loop radius R₀ kept, so that every loop has as many bodies),
//! and the knot settled on each branch at the pull the law gives there with σ = 0.492 (the
//! tightening pull ramped slowly enough to close the loop quasi-statically, from the torus or,
//! with `--tighten-from-looser`, from the loop the loosening law holds at ε/1.5). Prints,
//! as Markdown, a row per run with the ε and the friction number (F h²/B − ε⁴/2)/(μσε³) it
//! settled at (Audoly's ±1), the loop measured two ways: at its points ⊥ the pull, and by its
//! first integral H, R = √(B/(2H)) (`hagfish_validation::loose_knot`), with H's spread along
//! the loop, and beside each friction number the braid's normal-force number N h²/(σBε³)
//! (N the self contacts' normal forces summed): Coulomb's bound on it, and Audoly's σ at
//! leading order. With `--control`, each run also gets its frictionless control
//! (the same rod at F₀ = B/(2R²), R its loop radius at the ⊥ points; none where it has none)
//! and the friction number against it, (F h²/B − cε⁴)/(μσε³) with the control's
//! c = F₀R₀²/B for Audoly's ½: friction's own share, and the control braid's normal-force
//! number. Each run's ε and friction number (by H where it has one) go to stderr as it ends.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use hagfish_validation::ValidationError;
use hagfish_validation::frictional_knot::{
    AtEpsilon, Branch, FrictionalKnot, FrictionlessControl, LoopMeasure, TighteningStart,
};
use hagfish_validation::loose_knot::{self, Refinement};

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
    /// Where the tightening ramp starts.
    pub tightening_start: TighteningStart,
    /// Edges of the friction pyramid.
    pub edges: usize,
    /// Bodies and time step instead of the rod file's and the scenario's.
    pub resolution: Refinement,
    /// Whether each run gets its frictionless control.
    pub control: bool,
    /// Runs at a time.
    pub jobs: usize,
}

/// A run's frictionless control: `None` where the run itself failed.
type Control = Option<Result<FrictionlessControl, ValidationError>>;

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
                (request.ramp_s, request.tightening_start),
            );
            let resolution = request.resolution;
            std::iter::once(tightening)
                .chain(loosening)
                .map(move |run| AtEpsilon { resolution, ..run })
        })
        .collect()
}

/// Runs every case and prints the table.
pub fn run(root: &Path, request: &Request<'_>) -> Result<(), String> {
    let cases = cases(request, loose_knot::bending_stiffness(root).map_err(|e| e.to_string())?);
    let knots = in_parallel(&cases, request.jobs, |case| {
        let (clock, knot) = (Instant::now(), case.run(root, request.edges));
        eprintln!("{}", progress(case, &knot, clock.elapsed().as_secs_f64()));
        knot
    })?;
    let controls = if request.control {
        let runs: Vec<_> = cases.iter().zip(&knots).collect();
        Some(in_parallel(&runs, request.jobs, |(case, knot)| -> Control {
            // A control is pulled for the loop radius at the ⊥ points: none without them.
            let knot = knot.as_ref().ok().filter(|knot| knot.perpendicular.is_some())?;
            Some(knot.frictionless_control(root, case.refinement()))
        })?)
    } else {
        None
    };
    println!("{}", table(&cases, &knots, controls.as_deref()));
    let resolution = request.resolution;
    println!(
        "`cargo xtask audoly --mu {} --epsilon {} --loop-radius {} --ramp {} --edges {}{}{}{}{}`: \
         the loose trefoil (data/validation/loose_trefoil.ron, data/rods/loose.ron with h = \
         ε²R₀)",
        comma_list(request.coefficients),
        comma_list(request.epsilons),
        request.loop_radius_cm,
        request.ramp_s,
        request.edges,
        resolution.bodies.map_or_else(String::new, |n| format!(" --bodies {n}")),
        resolution.time_step_s.map_or_else(String::new, |h| format!(" --time-step {h}")),
        match request.tightening_start {
            TighteningStart::Torus => "",
            TighteningStart::Looser => " --tighten-from-looser",
        },
        if request.control { " --control" } else { "" },
    );
    Ok(())
}

/// The line printed to stderr as `case`'s run ends after `wall_s` seconds, so that a long set
/// of runs shows its progress.
fn progress(
    case: &AtEpsilon,
    knot: &Result<FrictionalKnot, ValidationError>,
    wall_s: f64,
) -> String {
    let (mu, epsilon) = (case.coefficient, case.target_epsilon);
    let branch = match case.branch {
        Branch::Tightening { .. } => "tightening",
        Branch::Loosening { .. } => "loosening",
    };
    let outcome = match knot {
        Ok(knot) => match knot.first_integral.as_ref().or(knot.perpendicular.as_ref()) {
            Some(m) => format!(
                "ε {:.4}, friction number {:+.3}, normal-force number {:.3}",
                m.epsilon, m.friction_number, m.normal_force_number
            ),
            None => "no loop to measure".to_string(),
        },
        Err(error) => format!("failed: {error}"),
    };
    format!("audoly: μ = {mu}, target ε = {epsilon}, {branch}: {outcome} ({wall_s:.0} s)")
}

/// The Markdown table: a row per run (a run that failed, with why) with its loop measured
/// at the points ⊥ the pull and by its first integral H, and with `controls` each run's
/// frictionless control and its friction number against it.
fn table(
    cases: &[AtEpsilon],
    knots: &[Result<FrictionalKnot, ValidationError>],
    controls: Option<&[Control]>,
) -> String {
    let mut out = String::from(
        "| μ | target ε | h (cm) | branch | F (dyn) | at ⊥: R (cm), ε | friction number | \
         N h²/(σBε³) | by H: R (cm), ε | friction number | N h²/(σBε³) | H's spread on the loop |",
    );
    out.push_str(if controls.is_some() {
        " control: R₀ (cm), F₀R₀²/B | N₀ h²/(σBε₀³) | number against it |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
    } else {
        "\n|---|---|---|---|---|---|---|---|---|---|---|---|\n"
    });
    let measure = |m: Option<&LoopMeasure>| match m {
        Some(m) => format!(
            "{:.4}, {:.4} | {:+.3} | {:.3}",
            m.loop_radius_cm, m.epsilon, m.friction_number, m.normal_force_number
        ),
        None => "no joint to measure | — | —".to_string(),
    };
    for (k, (case, knot)) in cases.iter().zip(knots).enumerate() {
        let branch = match case.branch {
            Branch::Tightening { ramp_s, from_dyn: None } => {
                format!("tightening, ramped over {ramp_s} s")
            }
            Branch::Tightening { ramp_s, from_dyn: Some(from_dyn) } => {
                format!("tightening from {from_dyn:.2} dyn, ramped over {ramp_s} s")
            }
            Branch::Loosening { from_dyn } => format!("loosening from {from_dyn:.1} dyn"),
        };
        let settled = match knot {
            Ok(knot) => format!(
                "{} | {} | {}",
                measure(knot.perpendicular.as_ref()),
                measure(knot.first_integral.as_ref()),
                knot.first_integral_spread
                    .map_or_else(|| "—".to_string(), |s| format!("{:.1} %", 100.0 * s)),
            ),
            Err(error) => format!("failed: {error} | — | — | — | — | — | —"),
        };
        let control = match (controls.map(|c| &c[k]), knot) {
            (None, _) => String::new(),
            (Some(Some(Ok(control))), Ok(knot)) => {
                let against = knot
                    .controlled_friction_number(control)
                    .map_or_else(|_| "—".to_string(), |n| format!("{n:+.3}"));
                format!(
                    " {:.4}, {:.4} | {:.3} | {against} |",
                    control.loop_radius_cm, control.tension_number, control.normal_force_number
                )
            }
            (Some(Some(Err(error))), _) => format!(" failed: {error} | — | — |"),
            (Some(_), _) => " — | — | — |".to_string(),
        };
        let _ = writeln!(
            out,
            "| {} | {} | {:.4} | {branch} | {:.2} | {settled} |{control}",
            case.coefficient, case.target_epsilon, case.rod_radius_cm, case.tension_dyn,
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_progress_line_names_its_run_and_outcome() {
        let case = AtEpsilon {
            coefficient: 0.03,
            target_epsilon: 0.05,
            rod_radius_cm: 0.01,
            branch: Branch::Tightening { ramp_s: 60.0, from_dyn: Some(0.07) },
            tension_dyn: 4.97,
            resolution: Refinement::default(),
        };
        let failed = Err(ValidationError::Scenario { path: "x".into(), reason: "lost".into() });
        let line = progress(&case, &failed, 12.3);
        assert!(
            line.starts_with("audoly: μ = 0.03, target ε = 0.05, tightening: failed"),
            "{line}"
        );
        assert!(line.contains("lost") && line.ends_with("(12 s)"), "{line}");
    }

    #[test]
    fn a_locked_loosening_branch_has_no_run() {
        // μ = 0.2 locks a knot at ε ≤ 2μσ = 0.197: only its tightening run.
        let request = Request {
            coefficients: &[0.2],
            epsilons: &[0.1, 0.3],
            loop_radius_cm: 2.0,
            ramp_s: 60.0,
            tightening_start: TighteningStart::Torus,
            edges: 8,
            resolution: Refinement::default(),
            control: false,
            jobs: 1,
        };
        let cases = cases(&request, 100.0);
        let branches: Vec<_> = cases.iter().map(|c| (c.target_epsilon, c.branch)).collect();
        assert_eq!(branches.len(), 3, "{branches:?}");
        assert!(matches!(branches[0], (0.1, Branch::Tightening { .. })));
        assert!(matches!(branches[2], (0.3, Branch::Loosening { .. })));
        assert!((cases[1].rod_radius_cm - 0.18).abs() < 1e-12);
    }

    #[test]
    fn the_control_columns_give_the_number_against_the_control() {
        let case = AtEpsilon {
            coefficient: 0.1,
            target_epsilon: 0.2,
            rod_radius_cm: 0.08,
            branch: Branch::Tightening { ramp_s: 60.0, from_dyn: None },
            tension_dyn: 20.0,
            resolution: Refinement::default(),
        };
        let knot = FrictionalKnot {
            branch: case.branch,
            tension_dyn: 20.0,
            coefficient: 0.1,
            perpendicular: Some(LoopMeasure {
                loop_radius_cm: 2.0,
                epsilon: 0.2,
                friction_number: 1.0,
                normal_force_number: 1.1,
            }),
            first_integral: Some(LoopMeasure {
                loop_radius_cm: 1.9,
                epsilon: 0.205,
                friction_number: 1.2,
                normal_force_number: 1.3,
            }),
            first_integral_spread: Some(0.004),
            rod_radius_cm: 0.08,
            bending_stiffness_dyn_cm2: 100.0,
        };
        let control = FrictionlessControl {
            tension_dyn: 12.5,
            loop_radius_cm: 2.01,
            tension_number: 0.55,
            normal_force_number: 1.05,
        };
        let against = knot.controlled_friction_number(&control).expect("a ⊥ measure");
        let printed = table(&[case], &[Ok(knot)], Some(&[Some(Ok(control))]));
        let row = printed.lines().nth(2).expect("a row");
        assert!(row.ends_with(&format!("| 2.0100, 0.5500 | 1.050 | {against:+.3} |")), "{row}");
        assert!(row.contains("| 2.0000, 0.2000 | +1.000 | 1.100 |"), "{row}");
        assert!(row.contains("| 1.9000, 0.2050 | +1.200 | 1.300 | 0.4 % |"), "{row}");
        assert_eq!(printed.lines().next().map(|h| h.matches('|').count()), Some(16));
        assert_eq!(printed.lines().nth(1).map(|h| h.matches('|').count()), Some(16));
        assert_eq!(row.matches('|').count(), 16, "{row}");
        let plain = table(
            &[case],
            &[Err(ValidationError::Scenario { path: "x".into(), reason: "y".into() })],
            None,
        );
        assert_eq!(plain.lines().next().map(|h| h.matches('|').count()), Some(13));
        assert_eq!(plain.lines().nth(1).map(|h| h.matches('|').count()), Some(13));
        assert_eq!(plain.lines().nth(2).map(|row| row.matches('|').count()), Some(13));
    }
}
