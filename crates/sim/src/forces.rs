//! Generalized constraint forces per group and DOF, labelled the way the thesis plots them
//! (Figure 6.2): joint j pairs the twist joint 2j (axis X) with the bend joint 2j + 1 (axes Y
//! and Z), so the ES103 body has joints 0…49 from head to tail, each with X, Y and Z.

use crate::rows::RowGroup;
use glam::DVec3;
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

/// Arc length of each DOF's joint from the head body's centre (cm), read off the body
/// `centres` at rest (straight): tree joint i sits halfway between centres i − 1 and i
/// (joint 0 at the wall), s = |½(cᵢ₋₁ + cᵢ) − c₀|, and `dof_joint` names each DOF's tree
/// joint. This is the arc-length convention of `hagfish_control::KnotSpan`; `hagfish modes` places the
/// force field's DOFs along the body with it.
pub fn dof_arc_lengths(centres: &[DVec3], dof_joint: &[usize]) -> Vec<f64> {
    let joint_arc = |i: usize| match i {
        0 => -centres[0].length(),
        _ => (0.5 * (centres[i - 1] + centres[i]) - centres[0]).length(),
    };
    dof_joint.iter().map(|&joint| joint_arc(joint)).collect()
}

/// [`dof_arc_lengths`] of `model` straight at rest (q = 0): the arc lengths `hagfish modes`
/// places a force field's DOFs at, and those a modal force space is resampled at.
pub fn rest_dof_arc_lengths(model: &Model) -> Vec<f64> {
    let mut data = hagfish_tree::Data::new(model);
    hagfish_tree::position_kinematics(model, &vec![0.0; model.dof_count()], &mut data);
    let centres: Vec<_> = (0..model.body_count()).map(|b| data.body_centre(b)).collect();
    dof_arc_lengths(&centres, model.dof_joint())
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

/// Generalized forces of the recorded groups averaged over a recording interval (dyn·cm per
/// rotational DOF): `f_g = Σ_k C_gᵀλ_g,k / (K h)` over the K steps since the previous frame.
/// Single steps alias badly at a 0.1 s frame rate (a contact force can be zero one step and
/// a few thousand dyn·cm the next); the mean is the force the frame interval felt.
#[derive(Clone, Debug, Default)]
pub struct GroupForces {
    /// One vector per group of [`RECORDED_GROUPS`], indexed like `q`: the summed impulses
    /// until [`GroupForces::finish_interval`], the mean forces after it.
    pub values: [Vec<f64>; 3],
    /// Steps summed in the current interval.
    steps: usize,
}

impl GroupForces {
    /// Adds the impulses `C_gᵀλ_g` of the step just solved.
    pub fn add_step(&mut self, data: &StepData, dofs: usize) {
        self.add_impulses(data, dofs);
        self.steps += 1;
    }

    /// Adds the impulses of the last (sub)step of `data` without counting a step: the
    /// substeps of one step add their impulses, and the step is counted once
    /// ([`GroupForces::count_as_one_step`]).
    /// A self contact's force is its core row's and, where the body has a skin, its skin row's:
    /// both are recorded as the contact group's.
    pub fn add_impulses(&mut self, data: &StepData, dofs: usize) {
        for (values, group) in self.values.iter_mut().zip(RECORDED_GROUPS) {
            values.resize(dofs, 0.0);
            let skin =
                (group == RowGroup::Contact && data.skin.is_present()).then_some(RowGroup::Skin);
            for member in std::iter::once(group).chain(skin) {
                let impulses = data.solver.tag_impulse(member.tag());
                values.iter_mut().zip(impulses).for_each(|(value, impulse)| *value += impulse);
            }
        }
    }

    /// Counts the impulses added since the last [`GroupForces::clear`] as one step.
    pub fn count_as_one_step(&mut self) {
        self.steps = 1;
    }

    /// Adds the impulses and steps of `other` (a retried step's substeps).
    pub fn absorb(&mut self, other: &GroupForces, dofs: usize) {
        for (values, added) in self.values.iter_mut().zip(&other.values) {
            values.resize(dofs, 0.0);
            values.iter_mut().zip(added).for_each(|(value, a)| *value += a);
        }
        self.steps += other.steps;
    }

    /// Turns the summed impulses into mean forces over the interval's steps of `time_step`
    /// (zero forces for an interval without steps, e.g. frame 0), sized for `dofs` DOFs.
    pub fn finish_interval(&mut self, dofs: usize, time_step: f64) {
        let duration = self.steps as f64 * time_step;
        for values in &mut self.values {
            values.resize(dofs, 0.0);
            if duration > 0.0 {
                values.iter_mut().for_each(|v| *v /= duration);
            }
        }
    }

    /// Starts the next interval.
    pub fn clear(&mut self) {
        self.values.iter_mut().for_each(|values| values.fill(0.0));
        self.steps = 0;
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
            RowGroup::Skin => "skin",
            RowGroup::Grip => "grip",
        }
    }
}
