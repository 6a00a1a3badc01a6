//! The breaks of rows built from points and joints (`hagfish_solver::WrenchBreaks`): where a
//! row's coefficients may stop being one wrench's generalized force, promised to the solver so
//! that it compresses the DOF ranges between them.

use hagfish_solver::{Rows, WrenchBreaks};
use hagfish_tree::Model;

/// The breaks of a row made of the velocities of points on `bodies`: the end of each body's
/// joint DOFs (`None`, no promise, for more bodies than a row may list).
pub(crate) fn point_breaks(
    model: &Model,
    bodies: impl IntoIterator<Item = usize>,
) -> Option<WrenchBreaks> {
    WrenchBreaks::new(bodies.into_iter().map(|body| model.joints()[body].dofs().end))
}

/// The breaks of a row on the DOFs of the joint holding DOF `dof` alone: that joint's first
/// and end DOF.
pub(crate) fn joint_breaks(model: &Model, dof: usize) -> Option<WrenchBreaks> {
    let dofs = model.joints()[model.dof_joint()[dof]].dofs();
    WrenchBreaks::new([dofs.start, dofs.end])
}

/// Promises `breaks` (if any) for the last row pushed.
pub(crate) fn set_last_breaks(rows: &mut Rows, breaks: Option<WrenchBreaks>) {
    if let (Some(last), Some(breaks)) = (rows.len().checked_sub(1), breaks) {
        rows.set_breaks(last, breaks);
    }
}
