//! `cargo xtask <task>`: project tasks that are programs rather than tests.
//!
//! - `regress [--check | --bless] [SCENARIO…]`: runs every scenario of `data/scenarios`,
//!   compares its metrics with the golden in `data/regress/<scenario>.ron` (`--check`, the
//!   default) or rewrites the goldens (`--bless`). See `regress.rs`.
//! - `test`: the project's one test command — finds or installs Chromium, then runs the
//!   regression and `cargo test --workspace --release` (`test_all.rs`).
//! - `knotted [--export PATH] [--steps N] [--repeat R] [--time-step H] [--backend B]`: exports and times
//!   the knotted benchmark state (`knotted.rs`).
//! - `family [--measure slide|loosen-tighten|modes|cylinder] …`: runs a knot scenario on the family
//!   of bodies and prints its table (`family.rs`, `family_modes.rs`).
//! - `validate`: runs the checks against elastic-rod theory (`hagfish-validation`) and prints
//!   the table of `docs/validation.md`; fails if a check is outside its tolerance.
//! - `overhand [--turns N,…] [--speeds U,…] …`: Choi et al. 2021's overhand knots pulled tight
//!   (`overhand.rs`).
//! - `lock [--mu μ,…] [--bodies N] [--time-step H] [--edges E]`: the loose trefoil with
//!   friction tightened and let go, Audoly et al.'s loosening lock (`lock.rs`).
//! - `audoly [--mu μ,…] [--epsilon ε,…] [--loop-radius R₀] [--bodies N] [--time-step H]
//!   [--tighten-from-looser] [--control]`: the loose trefoil with friction on Audoly et al.'s two branches, the rod's
//!   radius set by ε (`audoly.rs`).
//! - `braid --radius H --force F [--bodies N] [--time-step H] [--export PATH]`: the frictionless
//!   loose trefoil settled at one pull, its braid's normal force, for a peer's check
//!   (`braid.rs`, `bench/peers/audoly_braid.py`).

mod audoly;
mod braid;
mod family;
mod family_cases;
mod family_cylinder;
mod family_modes;
mod golden;
mod knotted;
mod lock;
mod metrics;
mod overhand;
mod python;
mod regress;
mod table;
mod test_all;
mod tolerance;
mod validate;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use hagfish_modes::KindSelection;
use hagfish_sim::DynamicsBackend;
use hagfish_validation::frictional_knot::{FINAL_PULL_S, TighteningStart};
use hagfish_validation::loose_knot::Refinement;

/// Command line of `cargo xtask`.
#[derive(Parser)]
#[command(name = "cargo xtask", about = "hagfish project tasks")]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

/// The tasks.
#[derive(Subcommand)]
enum Task {
    /// Runs the scenarios and compares their metrics with the goldens in `data/regress`.
    Regress {
        /// Compare with the goldens and fail on a difference (the default).
        #[arg(long, conflicts_with = "bless")]
        check: bool,
        /// Rewrite the goldens from this build's results.
        #[arg(long)]
        bless: bool,
        /// Scenario names (file stems in `data/scenarios`); all when none are given.
        scenarios: Vec<String>,
    },
    /// Runs every test: finds or installs Chromium (for the report's browser test), then the
    /// scenario regression and `cargo test --workspace --release`.
    Test,
    /// Exports the knotted benchmark state as JSON and times passive steps from it.
    Knotted {
        /// Write the model and state as JSON to this file.
        #[arg(long)]
        export: Option<PathBuf>,
        /// Steps per timed run (0: no timing).
        #[arg(long, default_value_t = 100)]
        steps: usize,
        /// Timed runs from the knotted state.
        #[arg(long, default_value_t = 20)]
        repeat: usize,
        /// Time step of the timed runs (s).
        #[arg(long, default_value_t = 0.01)]
        time_step: f64,
        /// Dynamics backend of the timed runs: `sparse` (maximal coordinates, the default of
        /// every scenario) or `dense` (reduced).
        #[arg(long, value_parser = ["dense", "sparse"], default_value = "sparse")]
        backend: String,
    },
    /// Runs the checks against elastic-rod theory and prints their table (Markdown).
    Validate,
    /// Pulls Choi et al. 2021's overhand knots with n turns tight at each end speed and prints
    /// their tables (Markdown; docs/validation.md, "Overhand knots pulled tight").
    Overhand {
        /// Turns n of the knots (1…4).
        #[arg(long, value_delimiter = ',', default_values_t = [1, 2, 3, 4])]
        turns: Vec<usize>,
        /// Speeds of each end u (cm/s).
        #[arg(long, value_delimiter = ',', default_values_t = [0.3, 0.6, 0.9])]
        speeds: Vec<f64>,
        /// Time step (s).
        #[arg(long, default_value_t = 0.02)]
        time_step: f64,
        /// The pull force that ends a run (dyn).
        #[arg(long, default_value_t = 300.0)]
        stop_force: f64,
        /// The force (dyn) from which the run table looks for the force's largest fall: the
        /// default leaves out the start's slack; 200 also leaves out the start's jerk, so that
        /// a loop inversion on a pull past 300 dyn shows (docs/validation.md).
        #[arg(long, default_value_t = 20.0)]
        drop_from: f64,
        /// The forces (dyn) from which the third table counts the speeds' spread along the
        /// pull, a row each: the default is the whole pull from 50 dyn; 50,300 adds the tight
        /// knot alone on a pull past 300 dyn.
        #[arg(long, value_delimiter = ',', default_values_t = [50.0])]
        spread_from: Vec<f64>,
        /// Runs at a time.
        #[arg(long, default_value_t = 2)]
        jobs: usize,
        /// Write each run's samples to `DIR/n<N>_u<U>.csv`.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// An override of `data/validation/overhand_pull.ron` for every run, as `hagfish run
        /// --set` (repeatable), e.g. `--set 'body="/path/rod.ron"'`.
        #[arg(long = "set", value_name = "PATH=VALUE")]
        sets: Vec<String>,
    },
    /// Tightens the loose trefoil with friction, lets it go and prints whether it locks, for
    /// each μ (Markdown; docs/validation.md, "The loosening lock").
    Lock {
        /// The friction coefficients μ.
        #[arg(long = "mu", value_delimiter = ',', default_values_t = [0.11, 0.116, 0.117, 0.125])]
        coefficients: Vec<f64>,
        /// Bodies of the rod (the rod file's 400 if not given).
        #[arg(long)]
        bodies: Option<usize>,
        /// Time step (s; the scenario's 0.02 if not given).
        #[arg(long)]
        time_step: Option<f64>,
        /// Edges of the friction pyramid.
        #[arg(long, default_value_t = 8)]
        edges: usize,
        /// Runs at a time.
        #[arg(long, default_value_t = 2)]
        jobs: usize,
    },
    /// Settles the loose trefoil with friction on both branches at the pulls Audoly et al.'s
    /// law gives for each μ and ε (the rod's radius h = ε²R₀) and prints the friction numbers
    /// it settled at, the loop measured at its points ⊥ the pull and by its first integral
    /// (Markdown; docs/validation.md, "Loose trefoil with friction").
    Audoly {
        /// The friction coefficients μ.
        #[arg(long = "mu", value_delimiter = ',', default_values_t = [0.1, 0.2])]
        coefficients: Vec<f64>,
        /// The target ε = √(h/R₀). At 0.4 the tightening loop's two measures part and its
        /// number is not resolved (docs/validation.md).
        #[arg(long = "epsilon", value_delimiter = ',', default_values_t = [0.1, 0.2, 0.3, 0.4])]
        epsilons: Vec<f64>,
        /// The loop radius R₀ (cm) each rod's radius is chosen for.
        #[arg(long, default_value_t = 2.0)]
        loop_radius: f64,
        /// The tightening pull's ramp (s), within the final pull's 120 s: the shipped study's
        /// 1 s closes the loop dynamically; from 20 s on the number at ε ≈ 0.1 no longer moves.
        #[arg(long, default_value_t = 60.0)]
        ramp: f64,
        /// Start each tightening ramp from the loop the loosening branch holds at ε/1.5
        /// instead of the torus: at ε = 0.05 and μ ≥ 0.03 the loop opening from the torus
        /// stops short of the target, inside the range friction holds.
        #[arg(long)]
        tighten_from_looser: bool,
        /// Also settle each run's frictionless control (the same rod at F₀ = B/(2R²), R the
        /// run's loop radius) and print the friction number against it.
        #[arg(long)]
        control: bool,
        /// Edges of the friction pyramid.
        #[arg(long, default_value_t = 8)]
        edges: usize,
        /// Bodies of the rod (the rod file's 400 if not given): a thin rod's braid needs more.
        #[arg(long)]
        bodies: Option<usize>,
        /// Time step (s; the scenario's 0.02 if not given): a thin rod needs a smaller one, so
        /// that no strand passes through another within a step.
        #[arg(long)]
        time_step: Option<f64>,
        /// Runs at a time.
        #[arg(long, default_value_t = 2)]
        jobs: usize,
    },
    /// Settles the frictionless loose trefoil on a rod of radius h at the pull F and prints its
    /// braid's total normal force N, as N h²/(σBε³) with ε = (2Fh²/B)^¼ (Audoly's σ is its 1 at
    /// leading order), and its loop radius; with `--export`, writes them, the rod and its
    /// settled centreline as JSON (for `bench/peers/audoly_braid.py`).
    Braid {
        /// The rod's radius h (cm).
        #[arg(long)]
        radius: f64,
        /// The pull F (dyn).
        #[arg(long)]
        force: f64,
        /// Bodies of the rod (the rod file's 400 if not given).
        #[arg(long)]
        bodies: Option<usize>,
        /// Time step (s; the scenario's 0.02 if not given).
        #[arg(long)]
        time_step: Option<f64>,
        /// Where to write the JSON.
        #[arg(long)]
        export: Option<PathBuf>,
    },
    /// Runs a knot scenario on the family of bodies and time steps (ES103 and 15 variants)
    /// and prints its knot table (Markdown), as in docs/physics.md.
    Family {
        /// The scenario (tie → tighten → slide; tie → loosen → tighten for `--measure
        /// loosen-tighten`); a relative path not found from here is taken from the workspace
        /// root.
        #[arg(long, default_value = "data/scenarios/thesis.ron")]
        scenario: PathBuf,
        /// The knot it ties (its Rolfsen name: 3_1, 4_1).
        #[arg(long, default_value = "3_1")]
        knot: String,
        /// An override for every run, as `hagfish run --set` (repeatable).
        #[arg(long = "set", value_name = "PATH=VALUE")]
        sets: Vec<String>,
        /// Runs at a time.
        #[arg(long, default_value_t = 2)]
        jobs: usize,
        /// Only these members (their names in the table; repeatable); all when none is given.
        #[arg(long, value_name = "NAME")]
        only: Vec<String>,
        /// What to measure: `slide` (tie → tighten → slide), `loosen-tighten` (tie →
        /// loosen → tighten, each phase against a control run with its targets at zero),
        /// `modes` (the modes of a phase's force field and each basis against ES103's) or
        /// `cylinder` (a slide around the scenario's first cylinder: the knot's turns about it
        /// and its travel along it, e.g. `--scenario data/scenarios/pole.ron`).
        #[arg(
            long,
            value_parser = ["slide", "loosen-tighten", "modes", "cylinder"],
            default_value = "slide"
        )]
        measure: String,
        /// `--measure modes`: the phase decomposed.
        #[arg(long, default_value = "slide")]
        phase: String,
        /// `--measure modes`: a DOF kind to tabulate (bend-y, bend-z, twist; repeatable);
        /// all three when none is given.
        #[arg(long, value_name = "KIND", value_parser = str::parse::<KindSelection>)]
        kind: Vec<KindSelection>,
        /// `--measure slide`, `modes` or `cylinder`: runs per member, the unperturbed one and N − 1
        /// rounding perturbations of its time step, h(1 + j·1e-12) (the modes with the spread
        /// over them).
        #[arg(long, value_name = "N", default_value_t = 1)]
        rounding: usize,
    },
}

/// The workspace root (the parent of this package's directory). `cargo xtask` (a `cargo run`)
/// sets `CARGO_MANIFEST_DIR` for the process, which is read first: the path compiled in is
/// that of whichever checkout built the binary, and a checkout sharing a target directory
/// with another one (same sources, so cargo does not rebuild) would otherwise run the other's
/// files or fail on a directory that is gone.
fn workspace_root() -> PathBuf {
    let manifest = std::env::var_os("CARGO_MANIFEST_DIR")
        .map_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")), PathBuf::from);
    manifest.parent().map_or(manifest.clone(), PathBuf::from)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.task {
        Task::Regress { check: _, bless, scenarios } => {
            let mode = if bless { regress::Mode::Bless } else { regress::Mode::Check };
            regress::run(&workspace_root(), mode, &scenarios)
        }
        Task::Test => test_all::run(&workspace_root()).map(|()| true),
        Task::Knotted { export, steps, repeat, time_step, backend } => {
            let backend = match backend.as_str() {
                "sparse" => DynamicsBackend::SparseMaximal,
                _ => DynamicsBackend::DenseReduced,
            };
            let request =
                knotted::Request { export: export.as_deref(), steps, repeat, time_step, backend };
            knotted::run(&workspace_root(), &request).map(|()| true)
        }
        Task::Validate => validate::run(&workspace_root()),
        Task::Overhand {
            turns,
            speeds,
            time_step,
            stop_force,
            drop_from,
            spread_from,
            jobs,
            out,
            sets,
        } => {
            if let Some(n) = turns.iter().find(|n| !(1..=4).contains(*n)) {
                eprintln!("error: --turns {n}: the knots have 1 to 4 turns (data/knots/imc-der)");
                return ExitCode::from(2);
            }
            if let Some(f) = spread_from.iter().find(|f| !(f.is_finite() && **f >= 0.0)) {
                eprintln!("error: --spread-from {f}: a force in dyn, finite and ≥ 0");
                return ExitCode::from(2);
            }
            let request = overhand::Request {
                turns: &turns,
                speeds: &speeds,
                time_step,
                stop_force,
                drop_from,
                spread_from: &spread_from,
                jobs,
                out: out.as_deref(),
                sets: &sets,
            };
            overhand::run(&workspace_root(), &request).map(|()| true)
        }
        Task::Lock { coefficients, bodies, time_step, edges, jobs } => {
            if let Some(mu) = coefficients.iter().find(|mu| !(mu.is_finite() && **mu > 0.0)) {
                eprintln!("error: --mu {mu}: a friction coefficient must be positive");
                return ExitCode::from(2);
            }
            let refinement = Refinement { bodies, time_step_s: time_step, ..Refinement::default() };
            let request = lock::Request { coefficients: &coefficients, edges, refinement, jobs };
            lock::run(&workspace_root(), &request).map(|()| true)
        }
        Task::Braid { radius, force, bodies, time_step, export } => {
            let positive = |x: f64| x.is_finite() && x > 0.0;
            if !(positive(radius) && positive(force)) {
                eprintln!("error: --radius {radius} and --force {force} must be positive");
                return ExitCode::from(2);
            }
            let request = braid::Request {
                rod_radius_cm: radius,
                tension_dyn: force,
                resolution: Refinement { bodies, time_step_s: time_step, ..Refinement::default() },
                export: export.as_deref(),
            };
            braid::run(&workspace_root(), &request).map(|()| true)
        }
        Task::Audoly {
            coefficients,
            epsilons,
            loop_radius,
            ramp,
            tighten_from_looser,
            control,
            edges,
            bodies,
            time_step,
            jobs,
        } => {
            let positive = |x: &f64| x.is_finite() && *x > 0.0;
            if let Some(x) = coefficients.iter().chain(&epsilons).find(|x| !positive(x)) {
                eprintln!("error: --mu and --epsilon must be positive, not {x}");
                return ExitCode::from(2);
            }
            if !positive(&loop_radius) {
                eprintln!("error: --loop-radius {loop_radius}: a length in cm, positive");
                return ExitCode::from(2);
            }
            if !(ramp.is_finite() && (0.0..FINAL_PULL_S).contains(&ramp)) {
                eprintln!(
                    "error: --ramp {ramp}: seconds, from 0 to below the final pull's {FINAL_PULL_S}"
                );
                return ExitCode::from(2);
            }
            let request = audoly::Request {
                coefficients: &coefficients,
                epsilons: &epsilons,
                loop_radius_cm: loop_radius,
                ramp_s: ramp,
                tightening_start: if tighten_from_looser {
                    TighteningStart::Looser
                } else {
                    TighteningStart::Torus
                },
                edges,
                resolution: Refinement { bodies, time_step_s: time_step, ..Refinement::default() },
                control,
                jobs,
            };
            audoly::run(&workspace_root(), &request).map(|()| true)
        }
        Task::Family { scenario, knot, sets, jobs, only, measure, phase, kind, rounding } => {
            // A relative path that is not there from here is taken from the workspace root.
            let scenario =
                if scenario.exists() { scenario } else { workspace_root().join(scenario) };
            if measure != "modes" && (!kind.is_empty() || phase != "slide") {
                eprintln!("error: --phase and --kind are options of --measure modes");
                return ExitCode::from(2);
            }
            if measure == "loosen-tighten" && rounding != 1 {
                eprintln!("error: --rounding is an option of --measure slide, modes and cylinder");
                return ExitCode::from(2);
            }
            let measure = match measure.as_str() {
                "loosen-tighten" => family::Measure::LoosenTighten,
                "modes" => {
                    let kinds = if kind.is_empty() {
                        vec![KindSelection::BendY, KindSelection::BendZ, KindSelection::Twist]
                    } else {
                        kind
                    };
                    family::Measure::Modes(family_modes::ModesMeasure { phase, kinds })
                }
                "cylinder" => family::Measure::Cylinder,
                _ => family::Measure::Slide,
            };
            let request = family::Request {
                scenario: &scenario,
                knot: &knot,
                sets: &sets,
                jobs,
                only: &only,
                measure,
                rounding,
            };
            family::run(&workspace_root(), &request).map(|()| true)
        }
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
