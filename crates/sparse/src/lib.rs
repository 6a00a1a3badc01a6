//! Sparse maximal-coordinate backend of the velocity step (`docs/physics.md`
//! "Sparse maximal-coordinate backend").
//!
//! The state stays in reduced coordinates `(q, q̇)` — positions are integrated as
//! `q ← q + h q̇¹` exactly as on the dense path, so the joints never drift apart: that is the
//! drift control. Only the velocity solve changes: instead of forming the dense reduced
//! `M̃ = Jᵀ Ĩ J + hD + h²K` (O(n²) to build, O(n³) to factor), the linearly implicit Euler
//! system is posed on the body twists with the joints as constraints,
//!
//! ```text
//! [ Ĩ    0    Gᵀ ] [ V ]   [ 0 ]        Ĩ = blockdiag(I_i + h C_i)    (6 × 6 per body)
//! [ 0    K̃   −Sᵀ ] [ q̇ ] = [ f̃ ]        K̃ = hD + h²K                  (diagonal, per DOF)
//! [ G   −S    0  ] [ μ ]   [ 0 ]        G V − S q̇ = 0 ⇔ V_c = V_p + S_c q̇_c per joint
//! ```
//!
//! and eliminated along the tree ([`TreeFactor`]; no fill, symbolic factorisation = the
//! parent array, computed once per model), in O(bodies). The factor is handed to the
//! contact-space QP of `hagfish-solver` as a [`hagfish_solver::MassOperator`], so the
//! constrained paths (head, limits, contacts, thigmotaxis) share the dense path's code.
//!
//! Solving `M̃ x = f` for a chain of five rods joined by universal joints, and checking the
//! answer with the operator `M̃ x` (both O(bodies)):
//!
//! ```
//! use glam::DVec3;
//! use hagfish_sparse::TreeFactor;
//! use hagfish_tree::{
//!     BodySpec, Data, DofParams, JointKind, ModelBuilder, State, Transform, forward_kinematics,
//! };
//!
//! let mut builder = ModelBuilder::new();
//! for i in 0..5_usize {
//!     builder.add_body(BodySpec {
//!         parent: i.checked_sub(1),
//!         joint: JointKind::UniversalYz,
//!         joint_offset: Transform::from_translation(DVec3::X * if i == 0 { 0.0 } else { 1.0 }),
//!         body_offset: Transform::from_translation(DVec3::X * 0.5),
//!         mass: 1.0,
//!         principal_inertia: DVec3::new(0.01, 0.1, 0.1),
//!         radius: 0.1,
//!         length: 1.0,
//!         skin: None,
//!         dofs: vec![DofParams { stiffness: 2.0, damping: 0.1, ..DofParams::default() }; 2],
//!     });
//! }
//! let model = builder.build()?;
//! let mut state = State::rest(&model);
//! state.q.iter_mut().enumerate().for_each(|(a, q)| *q = 0.1 * a as f64);
//! let mut data = Data::new(&model);
//! forward_kinematics(&model, &state.q, &state.qdot, &mut data);
//!
//! let mut factor = TreeFactor::new(&model)?;
//! factor.assemble(&model, &data, 0.01);
//! factor.factor()?;
//! let f: Vec<f64> = (0..model.dof_count()).map(|a| (a as f64).sin()).collect();
//! let mut x = f.clone();
//! factor.solve_lower_column(&mut x);
//! factor.solve_upper_column(&mut x); // x = M̃⁻¹ f
//! let mut back = vec![0.0; f.len()];
//! factor.apply(&x, &mut back);
//! for (b, f) in back.iter().zip(&f) {
//!     assert!((b - f).abs() < 1e-12, "M̃ M̃⁻¹ f = {b}, f = {f}");
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod block;
mod error;
mod factor;
mod operator;

pub use error::SparseError;
pub use factor::TreeFactor;
