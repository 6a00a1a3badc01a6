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
//! **Invariant: a model, options and a state in; the next state and a step report out.** No
//! files and no scenario format: a [`World`] is built from a [`hagfish_tree::Model`] (from a
//! body file by `hagfish-anatomy`, or by hand) and stepped with any
//! [`hagfish_control::Controller`].
//!
//! A hundred steps of the ES103 hagfish at rest, its head at the wall:
//!
//! ```
//! use hagfish_control::Passive;
//! use hagfish_sim::{StepOptions, World};
//! use hagfish_tree::State;
//!
//! let body = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/hagfish/es103.ron");
//! let model = hagfish_anatomy::Body::load(body)?.to_model()?;
//! let state = State::rest(&model);
//! let mut world = World::new(model, StepOptions::default(), state)?;
//! for _ in 0..100 {
//!     world.step(&mut Passive)?;
//! }
//! assert!((world.state().t - 1.0).abs() < 1e-9);
//! let mut centres = Vec::new();
//! world.body_centres(&mut centres);
//! let head = glam::DVec3::new(0.5 * 42.4 / 100.0, 0.0, 0.0); // body 0's centre, ℓ/2 along +X
//! assert!(centres[0].distance(head) < 1e-6, "the head stays at the wall");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod acceptance;
mod backend;
mod carried_contacts;
mod contact_prediction;
mod error;
mod forces;
mod hash;
mod internal_forces;
mod maxima;
mod memory;
mod options;
pub mod pipeline;
mod report;
mod retry;
pub mod rows;
pub mod skin;
mod step_data;
mod stop;
mod warm_start;
mod world;

pub use acceptance::{EndOfStep, Rejection, StepAcceptance};
pub use backend::DynamicsBackend;
pub use error::SimError;
pub use forces::{
    DofLabel, GroupForces, RECORDED_GROUPS, dof_arc_lengths, dof_labels, rest_dof_arc_lengths,
};
pub use hash::{fnv1a64, state_hash};
pub use internal_forces::{GripLoad, InternalForces, JointLoad};
pub use maxima::IntervalMaxima;
pub use memory::{
    MemoryBound, MemoryHeadroom, available_memory, check_memory, step_memory_estimate,
};
pub use options::{FINEST_RESOLVED_CHAIN, RESOLVED_CLUSTER_BODIES, RootHold, StepOptions};
pub use report::{Stage, StageTimings, StepReport};
pub use retry::{Attempt, ContactResolution, RetryableController, StepOutcome, StepTally};
pub use skin::{ContactSkin, SkinLayer};
pub use step_data::StepData;
pub use stop::StopRequest;
pub use warm_start::{KeyedMultiplier, RowKey, WarmStart};
pub use world::World;
