//! # hagfish-scenario
//!
//! The scenario format of the hagfish simulator (`docs/architecture.md`). **Invariant: text
//! in, a checked world and its controller out** — a scenario file (RON) is read, its
//! `--set` overrides applied, every value checked with its `file:line:column`, its body file
//! loaded, and [`LoadedScenario::build`] gives the [`hagfish_sim::World`] at rest (or in its
//! [`InitialShape`]) and the [`hagfish_control::PhasedController`] of its phases. Nothing
//! here steps or records a run (`hagfish-run` does).
//!
//! Half a second of the shipped tie scenario, stepped by hand (what `hagfish run` does between
//! its recorded frames):
//!
//! ```
//! use hagfish_scenario::LoadedScenario;
//!
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/tie.ron");
//! let loaded = LoadedScenario::load(path)?;
//! let (mut world, mut controller) = loaded.build()?;
//! for _ in 0..50 {
//!     let report = world.step(&mut controller)?;
//!     assert!(report.max_self_penetration_relative < 0.1);
//! }
//! assert!((world.state().t - 0.5).abs() < 1e-9);
//! assert_eq!(controller.phase_name(), "tie");
//! # Ok::<(), hagfish_scenario::ScenarioError>(())
//! ```

mod error;
mod initial_shape;
mod knot_plan_file;
mod knot_template_file;
mod modal_space;
mod obstacles;
mod override_value;
mod overrides;
mod parameters;
mod polyline_shape;
mod referenced_files;
mod replay_file;
mod rounding;
mod scenario;
mod scenario_check;

pub use error::{ECHO_HEAD, ECHO_TAIL, ScenarioError, echo};
pub use initial_shape::{InitialShape, OpenTorusKnot};
pub use obstacles::{ObstacleSpec, SpinSpec};
pub use overrides::{Override, apply_overrides};
pub use parameters::{PARAMETERS, Parameter};
pub use polyline_shape::PolylineShape;
pub use rounding::{ROUNDING_STEP, rounding_perturbed_step};
pub use scenario::{LoadedScenario, MIN_TIME_STEP_S, Scenario};
