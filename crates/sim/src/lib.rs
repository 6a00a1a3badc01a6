//! # hagfish-sim
//!
//! The step pipeline of the hagfish simulator (`docs/architecture.md`): a [`World`] holds an
//! immutable tree [`hagfish_tree::Model`] and [`StepOptions`], the minimal
//! [`hagfish_tree::State`], and [`StepData`] for everything derived. One step runs named
//! stages ([`pipeline`]): kinematics → applied forces → dynamics (M̃, f̃) → contact detection
//! (centreline, self and wall contacts) → constraint rows (head, limits, wall, self contact;
//! [`rows`]) → velocity solve (Cholesky / KKT / QP, `hagfish-solver`) → integration.
//! CGS units throughout.

mod benchmark_state;
mod error;
mod forces;
mod options;
pub mod pipeline;
mod recorder;
mod report;
pub mod rows;
mod run;
mod scenario;
mod step_data;
mod world;

pub use benchmark_state::{KNOTTED_SCENARIO, KNOTTED_TIME_S, knotted_world};
pub use error::SimError;
pub use forces::{DofLabel, GroupForces, RECORDED_GROUPS, dof_labels};
pub use options::StepOptions;
pub use recorder::{
    CENTRELINE_HEADER, FORCES_HEADER, Frame, FrameSink, IntervalMaxima, METRICS_HEADER, Recorder,
};
pub use report::{StageTimings, StepReport};
pub use run::{KnotSample, Progress, RunSummary, run};
pub use scenario::{LoadedScenario, Scenario};
pub use step_data::StepData;
pub use world::World;
