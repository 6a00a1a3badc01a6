//! Velocity-level constraint solve of one step: rows grouped by kind, unconstrained / KKT / QP
//! paths, contact-space QP with a clarabel reference.
//!
//! # The problem
//!
//! One linearly implicit Euler step (docs/physics.md, "Time stepping" and "Constraint rows") needs the new reduced velocity q̇ from
//!
//! minimize ½ q̇ᵀM̃q̇ − q̇ᵀf̃ subject to the constraint rows,
//!
//! with M̃ = M_r + hD + h²K symmetric positive definite (n × n, n ≈ 150–300) and
//! f̃ = M_r q̇⁰ + h f_r. This crate sees only these matrices and the rows, never the kinematic
//! tree; row *builders* from the body model fill a [`Rows`] container.
//!
//! # Conventions
//!
//! - Row i: dense cᵢ ∈ ℝⁿ, right-hand side bᵢ, a [`RowKind`] and a [`RowSource`]: the
//!   caller's [`RowTag`] (what the row models, an opaque id the caller maps; reports count
//!   rows and sum impulses per tag in [`PerTag`] arrays) and the caller's id of the object
//!   that produced the row (which contact, which DOF). The solver interprets neither.
//!   `Equality`: cᵢᵀq̇ = bᵢ. `Inequality`: cᵢᵀq̇ ≥ bᵢ. `SoftInequality { weight }`:
//!   cᵢᵀq̇ + σᵢ ≥ bᵢ, σᵢ ≥ 0, cost weight·σᵢ — an exact penalty, equal to the hard solution
//!   whenever that is feasible with λᵢ < weight; in the dual the box 0 ≤ λᵢ ≤ weight, and
//!   "slack used" means λᵢ at the weight.
//! - Sign, for all rows: **M̃q̇ = f̃ + Cᵀλ**, λ ≥ 0 on (soft) inequalities, λ free on
//!   equalities. An inequality row pushes along +cᵢ; a row that stops motion gets λ > 0.
//! - λ are impulses. The workspace returns the generalized impulse C_gᵀλ_g of each group;
//!   the generalized force (dyn·cm per rotational DOF) is C_gᵀλ_g / h, formed by the caller.
//! - Units are whatever the caller uses (CGS in hagfish); tolerances are relative.
//!
//! # Paths
//!
//! M̃ is a dense matrix or a [`MassOperator`] that brings its own factor M̃ = L Lᵀ (see
//! [`Mass`]); every path below needs only L⁻¹, L⁻ᵀ and M̃x.
//!
//! No rows → Cholesky. Equalities only → KKT by the Schur complement on the Cholesky of M̃.
//! Any (soft) inequality → QP by the contact-space dual (fast, default) or clarabel
//! (reference), selected by [`QpBackend`]. The contact-space dual
//! min ½λᵀ(C M̃⁻¹Cᵀ)λ − λᵀ(b − C M̃⁻¹f̃) over the box of λ is solved by a primal active-set
//! method with exact handling of linearly dependent rows (duplicated contacts), finished by
//! iterative refinement and a primal verification; it warm-starts from the previous λ. See
//! [`SolverWorkspace`] for the pipeline and [`SolveReport`] for what comes back. Malformed
//! input is a [`SolverError`]; every outcome of a well-formed problem (including infeasible)
//! is a [`SolveStatus`], never a panic.
//!
//! # Example
//!
//! ```
//! use faer::Mat;
//! use hagfish_solver::{
//!     Problem, RowKind, RowSource, RowTag, Rows, SolveStatus, SolverWorkspace,
//! };
//!
//! // One DOF pushed into a wall: f̃ = −1, row q̇ ≥ 0, tagged with the caller's own kind.
//! const WALL: RowTag = RowTag::new(0);
//! let mass = Mat::<f64>::identity(1, 1);
//! let mut rows = Rows::new(1);
//! rows.push(RowKind::Inequality, RowSource::new(WALL, 0), 0.0, &[1.0])?;
//! let problem = Problem::new(mass.as_ref(), &[-1.0], &rows)?;
//! let mut workspace = SolverWorkspace::default();
//! let report = workspace.solve(&problem)?;
//! assert_eq!(report.status, SolveStatus::Solved);
//! assert_eq!(report.active_per_tag[WALL], 1);
//! assert!(workspace.velocity()[0].abs() < 1e-12);
//! assert!(workspace.multipliers()[0] > 0.0);
//! # Ok::<(), hagfish_solver::SolverError>(())
//! ```

mod active_set;
mod clarabel_reference;
mod contact_space;
mod error;
mod free_set;
mod linalg;
mod mass_factor;
mod mass_operator;
mod options;
mod problem;
mod pyramid;
mod reduced_rows;
mod refine;
mod report;
mod residuals;
mod row_coefficients;
mod rows;
mod workspace;
mod wrench_breaks;

pub use error::SolverError;
pub use mass_operator::{FactoredMass, Mass, MassOperator};
pub use options::{QpBackend, SolverOptions, WarmStart};
pub use problem::Problem;
pub use pyramid::FrictionPyramid;
pub use report::{Residuals, SlackUsage, SolvePath, SolveReport, SolveStatus};
pub use row_coefficients::RowCoefficients;
pub use rows::{PerTag, RowBasis, RowKind, RowSource, RowTag, Rows};
pub use workspace::{Factored, SolverWorkspace};
pub use wrench_breaks::{MAX_BREAKS, WrenchBreaks};
