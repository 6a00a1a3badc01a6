//! # hagfish-tree
//!
//! A multibody tree in reduced (joint) coordinates, after REDMAX (Wang et al. 2019), with
//! CGS units throughout: cm, g, s; forces in dyn, torques in dyn·cm, angles in rad.
//!
//! - [`Model`] is immutable (bodies, joints, per-DOF springs, dampers and limits) and is made
//!   by a validating [`ModelBuilder`].
//! - [`State`] is minimal: `t`, `q`, `q̇`.
//! - [`Data`] holds everything derived from a state and all scratch, allocated once.
//!
//! A step is a sequence of stages, each a free function on `(&Model, &mut Data)`:
//! [`forward_kinematics`] → [`effective_mass`] → [`generalized_momentum`] →
//! [`generalized_force`] → [`assemble_effective_momentum`] → (constraint solve, in
//! `hagfish-solver`, or [`factor_effective_mass`] + [`solve_unconstrained`]) → [`integrate`].
//! [`step_unconstrained`] chains them.
//!
//! All motion vectors are world twists at the world origin ([`spatial`]); body-coordinate
//! Jacobians as in `docs/physics.md`, "Kinematics and dynamics" are available for analysis and tests ([`jacobian`]).

mod data;
pub mod dynamics;
mod error;
pub mod integrator;
pub mod jacobian;
mod joint;
pub mod joint_wrenches;
pub mod kinematics;
pub mod mass_matrix;
mod model;
pub mod spatial;
mod state;

pub use data::Data;
pub use dynamics::{generalized_force, generalized_momentum, inverse_dynamics, kinetic_energy};
pub use error::TreeError;
pub use integrator::{
    assemble_effective_momentum, factor_effective_mass, integrate, solve_unconstrained,
    step_unconstrained,
};
pub use joint::{DofParams, JointKind};
pub use joint_wrenches::joint_wrenches;
pub use kinematics::{forward_kinematics, position_kinematics, velocity_kinematics};
pub use mass_matrix::{effective_mass, mass_matrix};
pub use model::{Body, BodySpec, Joint, Model, ModelBuilder, PathToRoot};
pub use spatial::{RigidInertia, Spatial, SpatialComponents, Transform};
pub use state::State;
