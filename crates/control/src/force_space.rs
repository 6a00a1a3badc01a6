//! The generalized forces a thigmotaxis phase may exert: on every DOF (the thesis'
//! controller), or confined to a subspace — the forces that muscles of one kind can make, or
//! the span of the first k modes of a force field.

use std::path::PathBuf;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::dof_kind::KindSelection;
use crate::modal_basis::ModalBasis;

/// The space the thigmotaxic generalized force `f_th = C_thᵀλ` is confined to. Each
/// thigmotaxis row `c` is replaced by its projection `c̃ = P c` onto the space (`P` an
/// orthogonal projector), so that its force `c̃λ` lies in the space; the row then asks the
/// sliding speed of the projected velocity, `c̃ᵀq̇ = cᵀ(P q̇) ≥ v` (docs/physics.md,
/// "Confined thigmotaxis"). Not `Copy` since [`ForceSpace::Modes`] holds its basis behind an
/// `Arc`: cloning a request clones the `Arc`, which does not allocate.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum ForceSpace {
    /// Every DOF: `P = I`, the rows as the thesis builds them.
    #[default]
    Full,
    /// The bending DOFs only (`P` zeroes every twist DOF, the joints about the body's long
    /// axis): no twist torque, since the muscles that bend a hagfish are not the ones that
    /// would twist it.
    BendingOnly,
    /// The span of the first k mode shapes of a force field (`hagfish modes`' `modes.csv`),
    /// `P = B Bᵀ` with B (n × k) their orthonormalised samples at this body's DOFs:
    /// `c̃ = B(Bᵀc)`, O(nk) per row.
    Modes(ModalSpace),
}

/// A modal force space as a scenario writes it, e.g.
/// `Modes((file: "../runs/es103/modes/modes.csv", kind: "all", modes: 4))`, and its basis on
/// the body, which hagfish-scenario fills at load (never serialised: the scenario keeps the
/// spec, the built controller the matrix).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModalSpace {
    /// The `modes.csv` of `hagfish modes` (relative to the scenario file; absolute once
    /// loaded).
    pub file: PathBuf,
    /// The selection whose shapes are read (the file's `kind` column): its DOFs take the
    /// shapes' values, the others (the twists for `bend`, …) are zero in every mode.
    pub kind: KindSelection,
    /// k ≥ 1: the modes kept, the first k of the file's.
    pub modes: usize,
    /// The orthonormal basis B on this body's DOFs; `None` until the scenario is loaded,
    /// and a space without a basis is {0} (its rows exert no force).
    #[serde(skip)]
    pub basis: Option<Arc<ModalBasis>>,
}

impl PartialEq for ModalSpace {
    /// Two specs are equal when they name the same modes of the same file; the basis is a
    /// function of the spec and the body.
    fn eq(&self, other: &Self) -> bool {
        (&self.file, self.kind, self.modes) == (&other.file, other.kind, other.modes)
    }
}

impl ForceSpace {
    /// Projects the row `c` onto the space, `c ← P c`; `twist_dofs` are the indices of the
    /// twist DOFs (for `BendingOnly`), `scratch` holds at least k values (for `Modes`: `Bᵀc`).
    /// A `Modes` space whose basis was never resolved (made by hand rather than loaded with a
    /// scenario) is the zero space: its rows exert nothing. Allocates nothing.
    pub fn confine(&self, twist_dofs: &[usize], scratch: &mut [f64], row: &mut [f64]) {
        match self {
            ForceSpace::Full => {}
            ForceSpace::BendingOnly => twist_dofs.iter().for_each(|&k| row[k] = 0.0),
            ForceSpace::Modes(space) => match &space.basis {
                Some(basis) => basis.project(row, scratch),
                None => row.fill(0.0),
            },
        }
    }
}
