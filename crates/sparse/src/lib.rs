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

mod block;
mod error;
mod factor;
mod operator;

pub use error::SparseError;
pub use factor::TreeFactor;
