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
/// "Confined thigmotaxis"). This is the spec a scenario writes; the rows of each step carry its
/// [`Confinement`], which a request clones without allocating.
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
    /// The space as the rows use it: the spec without its file name, the basis shared.
    pub fn confinement(&self) -> Confinement {
        match self {
            ForceSpace::Full => Confinement::Full,
            ForceSpace::BendingOnly => Confinement::BendingOnly,
            ForceSpace::Modes(space) => Confinement::Modes(space.basis.clone()),
        }
    }
}

/// A [`ForceSpace`] as a thigmotaxis request carries it each step: cloning one clones at most an
/// `Arc` of the basis, which does not allocate (a [`ModalSpace`] would clone its file name).
#[derive(Clone, Debug, Default)]
pub enum Confinement {
    /// Every DOF.
    #[default]
    Full,
    /// The bending DOFs only.
    BendingOnly,
    /// The span of a modal basis; `None`, a basis never resolved, is the zero space.
    Modes(Option<Arc<ModalBasis>>),
}

impl PartialEq for Confinement {
    /// Equal kinds, and for modes the same basis (the same shared matrix, or both unresolved).
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (Confinement::Full, Confinement::Full) => true,
            (Confinement::BendingOnly, Confinement::BendingOnly) => true,
            (Confinement::Modes(a), Confinement::Modes(b)) => match (a, b) {
                (Some(a), Some(b)) => Arc::ptr_eq(a, b),
                (None, None) => true,
                _ => false,
            },
            _ => false,
        }
    }
}

impl Confinement {
    /// Projects the row `c` onto the space, `c ← P c`; `twist_dofs` are the indices of the
    /// twist DOFs (for `BendingOnly`), `scratch` holds at least k values (for `Modes`: `Bᵀc`).
    /// A `Modes` space whose basis was never resolved (made by hand rather than loaded with a
    /// scenario) is the zero space: its rows exert nothing. Allocates nothing.
    pub fn confine(&self, twist_dofs: &[usize], scratch: &mut [f64], row: &mut [f64]) {
        match self {
            Confinement::Full => {}
            Confinement::BendingOnly => twist_dofs.iter().for_each(|&k| row[k] = 0.0),
            Confinement::Modes(Some(basis)) => basis.project(row, scratch),
            Confinement::Modes(None) => row.fill(0.0),
        }
    }
}
