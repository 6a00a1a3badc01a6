//! # hagfish-sim
//!
//! The step pipeline of the hagfish simulator (`docs/architecture.md`): a [`World`] holds an
//! immutable tree [`hagfish_tree::Model`] and [`StepOptions`], the minimal
//! [`hagfish_tree::State`], and [`StepData`] for everything derived. One step runs named
//! stages ([`pipeline`]): kinematics → contact detection (centreline, self and wall contacts)
//! → control → dynamics (M̃, f̃) → constraint rows (head, limits, wall, self contact;
//! [`rows`]) → velocity solve (Cholesky / KKT / QP, `hagfish-solver`) → internal forces (the
//! load each joint transmits, [`JointLoad`]) → integration → the
//! result's check (its kinematics and contacts, kept for the next step; [`StepAcceptance`]).
//! CGS units throughout.
//!
//! Half a second of the shipped tie scenario, stepped by hand (what `hagfish run` does between
//! its recorded frames):
//!
//! ```
//! use hagfish_sim::LoadedScenario;
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
//! let mut centres = Vec::new();
//! world.body_centres(&mut centres);
//! let head = glam::DVec3::new(0.5 * 42.4 / 100.0, 0.0, 0.0); // body 0's centre, ℓ/2 along +X
//! assert!(centres[0].distance(head) < 1e-6, "the head stays at the wall");
//! # Ok::<(), hagfish_sim::SimError>(())
//! ```

mod acceptance;
mod backend;
mod checkpoint;
mod contact_prediction;
mod error;
mod force_columns;
mod force_field;
mod forces;
mod hash;
mod initial_shape;
mod internal_forces;
mod knot_core;
mod memory;
pub mod npy;
mod options;
mod output_file;
mod override_value;
mod overrides;
mod parameters;
pub mod pipeline;
mod recorder;
mod report;
pub mod rows;
mod run;
mod scenario;
mod scenario_check;
mod scientific;
mod step_data;
mod world;

pub use acceptance::{EndOfStep, Rejection, StepAcceptance};
pub use backend::DynamicsBackend;
pub use checkpoint::{CHECKPOINT_FILE, CHECKPOINT_FORMAT, Checkpoint, ExactF64s};
pub use error::SimError;
pub use force_field::{ForceFieldLog, ForceFieldStats};
pub use forces::{DofLabel, GroupForces, RECORDED_GROUPS, dof_labels};
pub use hash::state_hash;
pub use initial_shape::{InitialShape, OpenTorusKnot};
pub use internal_forces::{InternalForces, JointLoad};
pub use knot_core::KnotCore;
pub use memory::{available_memory, check_memory, step_memory_estimate};
pub use options::{FINEST_RESOLVED_CHAIN, RESOLVED_CLUSTER_BODIES, StepOptions};
pub use output_file::replace_file;
pub use overrides::{Override, apply_overrides};
pub use parameters::{PARAMETERS, Parameter};
pub use recorder::{
    CENTRELINE_HEADER, CONTACTS_HEADER, FORCES_HEADER, Frame, FrameSink, IntervalMaxima,
    METRICS_HEADER, RecordedFile, Recorder,
};
pub use report::{StageTimings, StepReport};
pub use run::{
    DEFAULT_MAX_STEPS, KnotSample, Progress, RunEnd, RunOptions, RunOutcome, RunSummary, run,
};
pub use scenario::{LoadedScenario, MIN_TIME_STEP_S, Scenario};
pub use step_data::StepData;
pub use world::World;
