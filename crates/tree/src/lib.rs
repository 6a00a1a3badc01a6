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
//! Jacobians as in `docs/physics.md`, "Kinematics and dynamics" are available for analysis
//! and tests ([`jacobian`]).
//!
//! A pendulum under gravity (a 1 g rod, 10 cm long, hinged at the origin about +Z), stepped
//! for a second: it swings down, and the pivot holds it.
//!
//! ```
//! use glam::DVec3;
//! use hagfish_tree::{
//!     BodySpec, Data, DofParams, JointKind, ModelBuilder, State, Transform, step_unconstrained,
//! };
//!
//! let mut builder = ModelBuilder::new().gravity(DVec3::new(0.0, -981.0, 0.0));
//! builder.add_body(BodySpec {
//!     parent: None,
//!     joint: JointKind::Revolute { axis: DVec3::Z },
//!     joint_offset: Transform::IDENTITY,
//!     body_offset: Transform::from_translation(DVec3::new(5.0, 0.0, 0.0)),
//!     mass: 1.0,
//!     principal_inertia: DVec3::new(0.005, 100.0 / 12.0, 100.0 / 12.0),
//!     radius: 0.1,
//!     length: 10.0,
//!     skin: None,
//!     dofs: vec![DofParams::default()],
//! });
//! let model = builder.build()?;
//! let (mut state, mut data) = (State::rest(&model), Data::new(&model));
//! for _ in 0..1000 {
//!     step_unconstrained(&model, &mut state, 1e-3, &mut data)?;
//! }
//! assert!(state.q[0] < -0.5, "it fell from horizontal: q = {}", state.q[0]);
//! let centre = data.body_centre(0);
//! assert!((centre.length() - 5.0).abs() < 1e-9, "the centre stays 5 cm from the pivot");
//! # Ok::<(), hagfish_tree::TreeError>(())
//! ```

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
mod pose;
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
pub use kinematics::{
    forward_kinematics, frame_kinematics, position_kinematics, velocity_kinematics,
};
pub use mass_matrix::{effective_mass, mass_matrix};
pub use model::{Body, BodySpec, Joint, Model, ModelBuilder, PathToRoot, Skin};
pub use pose::pose_along;
pub use spatial::{RigidInertia, Spatial, SpatialComponents, Transform};
pub use state::State;
