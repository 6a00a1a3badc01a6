//! Constraint rows built from the body model, one file per kind. Every row is written in the
//! solver's convention (`cᵀq̇ = b` or `cᵀq̇ ≥ b`, multipliers pushing along +c) straight into
//! the solver's [`hagfish_solver::Rows`] container, so building rows does not allocate.

mod breaks;
mod friction;
mod grip;
mod group;
mod head;
mod limits;
mod self_contact;
mod stabilisation;
mod thigmo;
mod wall;

pub use friction::{
    ConeForm, Friction, MAX_FRICTION_EDGES, contact_directions, wall_contact_offset,
};
pub use grip::{GripPush, add_grip_rows, grip_row_push, grip_wrench};
pub use group::RowGroup;
pub use head::add_head_rows;
pub use limits::{add_limit_rows, add_overshooting_limit_rows, overshoots_limit};
pub use self_contact::{add_self_contact_rows, add_spline_point_row};
pub use stabilisation::unilateral_rhs;
pub(crate) use thigmo::thigmo_strands;
pub use thigmo::{add_thigmo_rows, twist_dofs};
pub use wall::add_wall_rows;
