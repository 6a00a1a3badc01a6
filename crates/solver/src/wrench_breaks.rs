//! Where a row's coefficients stop being one wrench's generalized force: the promise that lets
//! the contact space compress the DOF ranges between contact points
//! (`contact_space/compressed_spans.rs`).
//!
//! In reduced coordinates on a body tree (DOF a a joint axis s_a, a world twist at the
//! origin), the velocity of a point moving with body t along a direction d is Jᵀ-like on
//! every joint of t's path to the root: its coefficient on DOF a is s_aᵀF with the wrench
//! F = (x × d; d) of a unit force d at the point. A row made of such point velocities (a
//! contact's, a wall's, a grip's, thigmotaxis rows) has c_a = s_aᵀF_a with F_a the sum of the
//! wrenches of its points at or beyond a's joint (a's subtree), which changes only where the
//! path passes a joint that carries a point. Its *breaks* are the DOF positions where it may
//! change: the end of each of those bodies' joint DOFs. A row on one joint's DOFs (a limit,
//! the head) has its breaks at that joint's first and end DOF.
//!
//! The promise: on every range [s, e) of a chain's DOFs with no break strictly inside
//! (s < p < e for no break p), the row's coefficients are s_aᵀF for one wrench F. Rows
//! without breaks ([`Rows`](crate::Rows) default) promise nothing; the contact space checks
//! what it compresses whether promised or not, so a wrong promise costs speed, not accuracy.

/// Most breaks one row may list: the bodies of two spline points (4 each), twice over.
pub const MAX_BREAKS: usize = 16;

/// The breaks of one row (module docs): DOF positions, each the end (or a joint's first) DOF of
/// a joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WrenchBreaks {
    positions: [usize; MAX_BREAKS],
    count: usize,
}

impl WrenchBreaks {
    /// The breaks at `positions` (repeats allowed), or `None` when there are more than
    /// [`MAX_BREAKS`] distinct ones (the row then promises nothing).
    pub fn new(positions: impl IntoIterator<Item = usize>) -> Option<Self> {
        let mut breaks = Self { positions: [0; MAX_BREAKS], count: 0 };
        for position in positions {
            if breaks.positions[..breaks.count].contains(&position) {
                continue;
            }
            *breaks.positions.get_mut(breaks.count)? = position;
            breaks.count += 1;
        }
        Some(breaks)
    }

    /// The breaks, distinct, in the order given.
    pub fn positions(&self) -> &[usize] {
        &self.positions[..self.count]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeats_are_kept_once_and_too_many_breaks_promise_nothing() {
        let breaks = WrenchBreaks::new([6, 3, 6, 9, 3]).expect("three distinct breaks");
        assert_eq!(breaks.positions(), &[6, 3, 9]);
        assert!(WrenchBreaks::new(0..MAX_BREAKS).is_some());
        assert_eq!(WrenchBreaks::new(0..=MAX_BREAKS), None);
        assert_eq!(WrenchBreaks::new([]).map(|b| b.positions().len()), Some(0));
    }
}
