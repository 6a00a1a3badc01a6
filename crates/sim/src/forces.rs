//! Generalized constraint forces per group and DOF, labelled the way the thesis plots them
//! (Figure 6.2): joint j pairs the twist joint 2j (axis X) with the bend joint 2j + 1 (axes Y
//! and Z), so the ES103 body has joints 0…49 from head to tail, each with X, Y and Z.

use glam::DVec3;
use hagfish_solver::RowGroup;
use hagfish_tree::{JointKind, Model};

use crate::step_data::StepData;

/// The thesis' label of a DOF: joint pair index and axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DofLabel {
    /// Joint index j (tree joint i belongs to j = i / 2).
    pub joint: usize,
    /// Axis of the DOF in its joint frame: 'X', 'Y' or 'Z'.
    pub axis: char,
}

/// Labels of every DOF of `model`, indexed like `q`.
pub fn dof_labels(model: &Model) -> Vec<DofLabel> {
    let mut labels = Vec::with_capacity(model.dof_count());
    for (i, joint) in model.joints().iter().enumerate() {
        for k in 0..joint.kind.dof_count() {
            let axis = match joint.kind {
                JointKind::UniversalYz => ['Y', 'Z'][k],
                _ => axis_name(joint.kind.axis(k)),
            };
            labels.push(DofLabel { joint: i / 2, axis });
        }
    }
    labels
}

fn axis_name(axis: DVec3) -> char {
    let a = axis.abs();
    if a.x >= a.y && a.x >= a.z {
        'X'
    } else if a.y >= a.z {
        'Y'
    } else {
        'Z'
    }
}

/// The groups whose forces are recorded (the head's bilateral force is not a control).
pub const RECORDED_GROUPS: [RowGroup; 3] = [RowGroup::Limit, RowGroup::Contact, RowGroup::Thigmo];

/// Generalized forces `C_gᵀλ_g / h` (dyn·cm per rotational DOF) of the recorded groups over
/// the last step.
#[derive(Clone, Debug, Default)]
pub struct GroupForces {
    /// One vector per group of [`RECORDED_GROUPS`], indexed like `q`.
    pub values: [Vec<f64>; 3],
}

impl GroupForces {
    /// Fills the forces from the last step's solve (zero before any step).
    pub fn fill(&mut self, data: &StepData, dofs: usize, time_step: f64) {
        for (values, group) in self.values.iter_mut().zip(RECORDED_GROUPS) {
            values.resize(dofs, 0.0);
            data.group_force(group, time_step, values);
        }
    }

    /// The forces of one recorded group (empty for a group that is not recorded).
    pub fn group(&self, group: RowGroup) -> &[f64] {
        RECORDED_GROUPS.iter().position(|g| *g == group).map_or(&[], |i| &self.values[i])
    }

    /// A short lowercase name of a group for tables.
    pub fn group_name(group: RowGroup) -> &'static str {
        match group {
            RowGroup::Head => "head",
            RowGroup::Limit => "limit",
            RowGroup::Wall => "wall",
            RowGroup::Contact => "contact",
            RowGroup::Thigmo => "thigmo",
        }
    }
}
