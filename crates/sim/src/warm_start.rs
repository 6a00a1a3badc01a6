//! The velocity solve's warm start, carried from one step to the next by what each row
//! constrains rather than by its position (issue #40, "a warm-started active set from the
//! previous step's"; docs/physics.md, "6 Velocity solve and re-solves", warm start).
//!
//! The active-set method starts from any λ inside its box; the previous step's λ puts the
//! previous contacts straight into its free set (`hagfish_solver`'s `active_set.rs`). Handed
//! over by row position, a contact found or lost ahead of others shifts every later row, so
//! each multiplier lands on another contact's row (on Choi et al.'s 9₁, ≈ 500 contacts of 8
//! pyramid edges, the first solve of each step then took ≈ 500 iterations). Here each row gets
//! a [`RowKey`] when its step's rows are built: its group, its place among the rows of its
//! object (a pyramid's edge), and where that object is — its id for the head, limits,
//! thigmotaxis and grip rows (a DOF, a request, an axis), its spline parameters (u_a, u_b) for
//! a self contact and its skin, u for a wall or obstacle contact. The next step's row takes the
//! multiplier of the last step's row with its group and ordinal whose place is nearest
//! (|Δu_a| + |Δu_b|, each within [`CONTACT_REACH`] segments; ids exactly), or 0.
//!
//! What is carried is a start, never trusted: any λ is clamped into the box and the method
//! runs to optimality from it. The keyed multipliers are part of the checkpoint
//! ([`WarmStart::carried`]), so a resumed run starts its next solve where the uninterrupted
//! run did.

use hagfish_geometry::{SelfContact, WallContact};
use hagfish_solver::{Rows, SolverWorkspace};

use crate::rows::RowGroup;

/// How far (in spline parameter, i.e. segments) a contact may have moved along either strand
/// in one step and still take over its multipliers: a knot slides a fraction of a segment
/// per step (ES103 at 2 cm/s and h = 0.01 s: 0.05 segment; Choi et al.'s rod pulled at
/// 1.8 cm/s with h = 0.02 s: 0.2 segment).
const CONTACT_REACH: f64 = 0.5;

/// What one row constrains, comparable from one step to the next.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RowKey {
    /// The row's group ([`RowGroup`], by its tag index).
    pub group: u8,
    /// Its place among the consecutive rows of its object (a friction pyramid's edge k).
    pub ordinal: u32,
    /// Where its object is: (u_a, u_b) of a self contact or its skin, (u, 0) of a wall or
    /// obstacle contact, (id, 0) otherwise.
    pub place: [f64; 2],
}

/// A row's key with the multiplier its last solve gave it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeyedMultiplier {
    /// What the row constrained.
    pub key: RowKey,
    /// Its multiplier λ (an impulse, dyn·s, or dyn·cm·s on a rotational DOF).
    pub lambda: f64,
}

/// The last step's multipliers by key, and the scratch of the next start (grow-only).
#[derive(Debug, Default)]
pub struct WarmStart {
    /// Sorted by [`order`]: group, ordinal, place, then λ.
    carried: Vec<KeyedMultiplier>,
    keys: Vec<RowKey>,
    start: Vec<f64>,
}

impl WarmStart {
    /// The multipliers carried to the next step, sorted by key (for the checkpoint).
    pub fn carried(&self) -> &[KeyedMultiplier] {
        &self.carried
    }

    /// Carries `multipliers` (a checkpoint's) to the next step, in any order.
    pub fn set_carried(&mut self, multipliers: &[KeyedMultiplier]) {
        self.carried.clear();
        self.carried.extend_from_slice(multipliers);
        self.carried.sort_unstable_by(order);
    }

    /// Gives `solver` the start of this step's first solve: each of `rows` the carried
    /// multiplier of its key's nearest match, or 0 (module docs).
    pub fn hand_to(
        &mut self,
        rows: &Rows,
        contacts: (&[SelfContact], &[WallContact]),
        solver: &mut SolverWorkspace,
    ) {
        self.keys.clear();
        extend_row_keys(rows, contacts, &mut self.keys);
        self.start.clear();
        let carried = &self.carried;
        self.start.extend(self.keys.iter().map(|key| nearest(carried, key).unwrap_or(0.0)));
        solver.set_multipliers(&self.start);
    }

    /// Keeps this step's `multipliers` (the last solve's, in the order of `rows`) for the next
    /// step. The rows are those [`WarmStart::hand_to`] keyed, with the limit rows a re-solve
    /// appended: only those get keys here.
    pub fn keep(
        &mut self,
        rows: &Rows,
        contacts: (&[SelfContact], &[WallContact]),
        multipliers: &[f64],
    ) {
        if self.keys.len() > rows.len() {
            self.keys.clear();
        }
        extend_row_keys(rows, contacts, &mut self.keys);
        self.carried.clear();
        let keyed = self.keys.iter().zip(multipliers);
        self.carried.extend(keyed.map(|(&key, &lambda)| KeyedMultiplier { key, lambda }));
        self.carried.sort_unstable_by(order);
    }
}

/// The order of the carried multipliers: group, ordinal, place, then the multiplier itself, a
/// total order (entries it cannot tell apart are equal), so that an in-place sort (no
/// allocation in the step) gives the same list from any order, a checkpoint's included.
fn order(a: &KeyedMultiplier, b: &KeyedMultiplier) -> std::cmp::Ordering {
    let (x, y) = (&a.key, &b.key);
    (x.group, x.ordinal)
        .cmp(&(y.group, y.ordinal))
        .then(x.place[0].total_cmp(&y.place[0]))
        .then(x.place[1].total_cmp(&y.place[1]))
        .then(a.lambda.total_cmp(&b.lambda))
}

/// The multiplier of the carried row with `key`'s group and ordinal whose place is nearest
/// to `key`'s within [`CONTACT_REACH`] in each parameter (the first of equally near ones), if
/// any.
fn nearest(carried: &[KeyedMultiplier], key: &RowKey) -> Option<f64> {
    let first = carried.partition_point(|c| {
        (c.key.group, c.key.ordinal) < (key.group, key.ordinal)
            || ((c.key.group, c.key.ordinal) == (key.group, key.ordinal)
                && c.key.place[0] < key.place[0] - CONTACT_REACH)
    });
    let candidates = carried[first..].iter().take_while(|c| {
        (c.key.group, c.key.ordinal) == (key.group, key.ordinal)
            && c.key.place[0] <= key.place[0] + CONTACT_REACH
    });
    let mut best: Option<(f64, f64)> = None;
    for c in candidates {
        let (d0, d1) =
            ((c.key.place[0] - key.place[0]).abs(), (c.key.place[1] - key.place[1]).abs());
        if d1 > CONTACT_REACH {
            continue;
        }
        if best.is_none_or(|(distance, _)| d0 + d1 < distance) {
            best = Some((d0 + d1, c.lambda));
        }
    }
    best.map(|(_, lambda)| lambda)
}

/// Appends to `keys` the key (module docs) of each of `rows` from `keys.len()` on.
fn extend_row_keys(
    rows: &Rows,
    (self_contacts, wall_contacts): (&[SelfContact], &[WallContact]),
    keys: &mut Vec<RowKey>,
) {
    let sources = rows.sources();
    for i in keys.len()..sources.len() {
        let source = sources[i];
        let ordinal = match keys.last() {
            Some(last) if sources[i - 1] == source => last.ordinal + 1,
            _ => 0,
        };
        let place = match RowGroup::of(source.tag) {
            Some(RowGroup::Contact | RowGroup::Skin) => {
                let contact = &self_contacts[source.id];
                [contact.u_a, contact.u_b]
            }
            Some(RowGroup::Wall) => [wall_contacts[source.id].u, 0.0],
            _ => [source.id as f64, 0.0],
        };
        keys.push(RowKey { group: source.tag.index() as u8, ordinal, place });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keyed(group: u8, ordinal: u32, place: [f64; 2], lambda: f64) -> KeyedMultiplier {
        KeyedMultiplier { key: RowKey { group, ordinal, place }, lambda }
    }

    fn carried(multipliers: &[KeyedMultiplier]) -> WarmStart {
        let mut warm = WarmStart::default();
        warm.set_carried(multipliers);
        warm
    }

    /// A contact that moved along both strands takes over the nearest carried contact's
    /// multiplier for the same edge; one beyond reach along either strand, another group or
    /// another edge gets nothing; ids match exactly.
    #[test]
    fn a_row_takes_the_multiplier_of_the_nearest_row_of_its_kind() {
        let contact = RowGroup::Contact.tag().index() as u8;
        let limit = RowGroup::Limit.tag().index() as u8;
        let warm = carried(&[
            keyed(contact, 0, [10.0, 40.0], 1.0),
            keyed(contact, 1, [10.0, 40.0], 2.0),
            keyed(contact, 0, [10.3, 44.0], 3.0),
            keyed(limit, 0, [7.0, 0.0], 4.0),
        ]);
        let at = |group, ordinal, place| nearest(&warm.carried, &RowKey { group, ordinal, place });
        assert_eq!(at(contact, 0, [10.2, 40.1]), Some(1.0));
        assert_eq!(at(contact, 1, [10.2, 40.1]), Some(2.0));
        assert_eq!(at(contact, 0, [10.25, 43.8]), Some(3.0));
        assert_eq!(at(contact, 0, [10.2, 40.6]), None, "beyond reach along the second strand");
        assert_eq!(at(contact, 0, [9.4, 40.0]), None, "beyond reach along the first strand");
        assert_eq!(at(contact, 2, [10.0, 40.0]), None, "an edge the contact did not have");
        assert_eq!(at(limit, 0, [7.0, 0.0]), Some(4.0));
        assert_eq!(at(limit, 0, [8.0, 0.0]), None, "another DOF's limit");
    }

    /// The checkpoint's order does not matter: carried multipliers are sorted on arrival, to
    /// the same list from any order even where keys are equal.
    #[test]
    fn carried_multipliers_are_found_in_any_order() {
        let contact = RowGroup::Contact.tag().index() as u8;
        let rows: Vec<KeyedMultiplier> = (0..20)
            .rev()
            .map(|k| keyed(contact, 0, [k as f64, 50.0 - k as f64], k as f64))
            .collect();
        let warm = carried(&rows);
        let mut ties = rows.clone();
        ties.extend(rows.iter().map(|m| KeyedMultiplier { lambda: -m.lambda, ..*m }));
        let reversed: Vec<KeyedMultiplier> = ties.iter().rev().copied().collect();
        assert_eq!(carried(&ties).carried, carried(&reversed).carried, "equal keys, any order");
        for k in 0..20 {
            let key =
                RowKey { group: contact, ordinal: 0, place: [k as f64 + 0.1, 49.9 - k as f64] };
            assert_eq!(nearest(&warm.carried, &key), Some(k as f64));
        }
    }
}
