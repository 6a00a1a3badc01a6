//! What a hagfish row models, mapped onto the solver's opaque [`RowTag`]s: the solver knows
//! nothing of heads, limits or contacts; the simulator tags its rows with these groups and
//! reads its reports back through them. Each row's [`RowSource`] id names the object the row
//! comes from (see [`RowGroup`]), so a multiplier is traced back without relying on row order.

use hagfish_solver::{PerTag, RowSource, RowTag};

/// The simulator's row groups, each one solver [`RowTag`] (its position in [`RowGroup::ALL`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum RowGroup {
    /// Head fixation (bilateral rows on the root DOFs); id: the DOF.
    Head,
    /// Joint limits; id: the DOF.
    Limit,
    /// Wall contact; id: the index in the step's wall contacts.
    Wall,
    /// Self contact on the centreline; id: the index in the step's self contacts.
    Contact,
    /// Thigmotaxic velocity targets; id: the index of the request in the step's actuation.
    Thigmo,
    /// The skin's spring at a self contact (docs/physics.md, "Skin"); id: the index in the
    /// step's self contacts (the same contact's core row is a [`RowGroup::Contact`] row).
    Skin,
    /// A grip on a body point (`hagfish_control::Grip`); id: the row's axis (0–2 force, 3–5
    /// moment; [`crate::rows::grip_row_push`]).
    Grip,
}

impl RowGroup {
    /// Number of groups.
    pub const COUNT: usize = 7;
    /// All groups in tag order.
    pub const ALL: [RowGroup; RowGroup::COUNT] = [
        RowGroup::Head,
        RowGroup::Limit,
        RowGroup::Wall,
        RowGroup::Contact,
        RowGroup::Thigmo,
        RowGroup::Skin,
        RowGroup::Grip,
    ];

    /// The solver tag of the group's rows.
    pub const fn tag(self) -> RowTag {
        RowTag::new(self as u8)
    }

    /// The source of the group's row that object `id` produced.
    pub const fn source(self, id: usize) -> RowSource {
        RowSource::new(self.tag(), id)
    }

    /// The values of a solver report's per-tag array for the groups, in [`RowGroup::ALL`]
    /// order (e.g. the rows per group of a step).
    pub fn values<T: Copy>(per_tag: &PerTag<T>) -> [T; RowGroup::COUNT] {
        Self::ALL.map(|group| per_tag[group.tag()])
    }

    /// The group tagged `tag`, if it is one of the simulator's.
    pub fn of(tag: RowTag) -> Option<RowGroup> {
        Self::ALL.into_iter().find(|group| group.tag() == tag)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_group_has_its_own_tag_and_comes_back_from_it() {
        for group in RowGroup::ALL {
            assert_eq!(RowGroup::of(group.tag()), Some(group));
        }
        assert_eq!(RowGroup::of(RowTag::new(RowGroup::COUNT as u8)), None);
    }
}
