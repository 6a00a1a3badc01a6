//! Which linear algebra carries the velocity step (`docs/physics.md`, "Sparse
//! maximal-coordinate backend"): the dense reduced `M̃` (CRBA + Cholesky, O(n²) + O(n³)) or
//! the tree-structured factor of the maximal-coordinate system (`hagfish-sparse`, O(n)). Both
//! give the same `q̇¹` for the same step up to rounding; the state stays reduced either way.

use hagfish_solver::{Problem, SolverError};
use hagfish_tree::Model;

use crate::step_data::StepData;

/// The backend of the dynamics and solve stages (a [`crate::StepOptions`] field, and the
/// `backend` of a scenario file).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum DynamicsBackend {
    /// Dense reduced `M̃ = M + h Jᵀ C_m J + hD + h²K` by CRBA, factored by dense Cholesky.
    /// Cubic in the number of bodies; the reference path (the goldens are blessed on it).
    #[default]
    DenseReduced,
    /// Body twists and joint constraints, `[Ĩ, 0, Gᵀ; 0, K̃, −Sᵀ; G, −S, 0]`, eliminated
    /// along the tree (`hagfish_sparse::TreeFactor`): linear in the number of bodies.
    SparseMaximal,
}

/// Whether a solve may keep the factor and the contact-space matrices of the last one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Reuse {
    /// M̃ or the rows changed: factor (sparse backend) and solve afresh.
    Nothing,
    /// Only f̃ changed since the last solve.
    MassAndRows,
}

/// Stage 4's effective mass for the backend: the dense `M̃` (CRBA) or the maximal system's
/// blocks `Ĩ_i = I_i + h C_i`, `K̃ = hD + h²K` and the axes.
pub(crate) fn assemble_effective_mass(model: &Model, data: &mut StepData, h: f64) {
    match &mut data.tree_factor {
        None => hagfish_tree::effective_mass(model, &mut data.tree, h),
        Some(factor) => factor.assemble(model, &data.tree, h),
    }
}

/// Stage 6's solve with the backend's `M̃`: the dense matrix (factored by the solver; when only
/// f̃ changed, not validated again), or the tree factor (factored here, O(n), unless only f̃
/// changed) as a [`hagfish_solver::MassOperator`].
pub(crate) fn solve(data: &mut StepData, reuse: Reuse) -> Result<(), SolverError> {
    let StepData { tree, tree_factor, rows, solver, report, .. } = data;
    let problem = match tree_factor {
        None if reuse == Reuse::MassAndRows => Problem::with_validated_mass_and_rows(
            tree.effective_mass.as_ref(),
            &tree.effective_momentum,
            rows,
        )?,
        None => Problem::new(tree.effective_mass.as_ref(), &tree.effective_momentum, rows)?,
        Some(factor) => {
            if reuse == Reuse::Nothing || !factor.is_factored() {
                factor.factor()?;
            }
            Problem::with_operator(&*factor, &tree.effective_momentum, rows)?
        }
    };
    report.solve = *match reuse {
        Reuse::Nothing => solver.solve(&problem)?,
        Reuse::MassAndRows => solver.solve_with_new_force(&problem)?,
    };
    Ok(())
}
