//! Which linear algebra carries the velocity step (`docs/physics.md`, "Sparse
//! maximal-coordinate backend"): the dense reduced `M̃` (CRBA + Cholesky, O(n²) + O(n³)) or
//! the tree-structured factor of the maximal-coordinate system (`hagfish-sparse`, O(n)). Both
//! give the same `q̇¹` for the same step up to rounding; the state stays reduced either way.

use faer::Mat;
use hagfish_solver::{Mass, SolverError};
use hagfish_sparse::TreeFactor;
use hagfish_tree::Model;

use crate::step_data::StepData;

/// The backend of the dynamics and solve stages (a [`crate::StepOptions`] field, and the
/// `backend` of a scenario file).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum DynamicsBackend {
    /// Dense reduced `M̃ = M + h Jᵀ C_m J + hD + h²K` by CRBA, factored by dense Cholesky.
    /// Cubic in the number of bodies: the reference that the sparse path is checked against.
    DenseReduced,
    /// Body twists and joint constraints, `[Ĩ, 0, Gᵀ; 0, K̃, −Sᵀ; G, −S, 0]`, eliminated
    /// along the tree (`hagfish_sparse::TreeFactor`): linear in the number of bodies. The
    /// default (the goldens are blessed on it).
    #[default]
    SparseMaximal,
}

/// Stage 4's effective mass for the backend: the dense `M̃` (CRBA) or the maximal system's
/// blocks `Ĩ_i = I_i + h C_i`, `K̃ = hD + h²K` and the axes.
pub(crate) fn assemble_effective_mass(model: &Model, data: &mut StepData, h: f64) {
    match &mut data.tree_factor {
        None => hagfish_tree::effective_mass(model, &mut data.tree, h),
        Some(factor) => factor.assemble(model, &data.tree, h),
    }
}

/// Stage 6's `M̃` for the solver: the dense matrix `dense` (factored by the solver), or the
/// tree factor, factored here (O(n)) unless it already is for this step's `M̃`.
pub(crate) fn mass<'a>(
    dense: &'a Mat<f64>,
    tree_factor: &'a mut Option<TreeFactor>,
) -> Result<Mass<'a>, SolverError> {
    match tree_factor {
        None => Ok(Mass::Dense(dense.as_ref())),
        Some(factor) => {
            if !factor.is_factored() {
                factor.factor()?;
            }
            Ok(Mass::Operator(&*factor))
        }
    }
}
