//! The generalized forces a thigmotaxis phase may exert: on every DOF (the thesis'
//! controller), or confined to a subspace — the forces that muscles of one kind can make.

use serde::{Deserialize, Serialize};

/// The space the thigmotaxic generalized force `f_th = C_thᵀλ` is confined to. Each
/// thigmotaxis row `c` is replaced by its projection `c̃ = P c` onto the space (`P` an
/// orthogonal projector), so that its force `c̃λ` lies in the space; the row then asks the
/// sliding speed of the projected velocity, `c̃ᵀq̇ = cᵀ(P q̇) ≥ v` (docs/physics.md,
/// "Confined thigmotaxis").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum ForceSpace {
    /// Every DOF: `P = I`, the rows as the thesis builds them.
    #[default]
    Full,
    /// The bending DOFs only (`P` zeroes every twist DOF, the joints about the body's long
    /// axis): no twist torque, since the muscles that bend a hagfish are not the ones that
    /// would twist it.
    BendingOnly,
}
