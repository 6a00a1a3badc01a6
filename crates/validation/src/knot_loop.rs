//! Where the loop of a knot pulled along an axis lies across the pull: Tong, Choi, Joo & Jawed
//! (2023, J. Appl. Mech. 90:041008) call the snap by which it moves from one side of the knot
//! to the other "inversion", the fall of the pull force that Choi et al. (2021) see for n = 3
//! and 4 turns.
//!
//! The braid is where the rod touches itself: its point is the mean of the self contacts'
//! midpoints. The loop is the longest run of bodies between the first and the last body a
//! contact touches (a contact at u touches the four bodies of its spline segment) that no
//! contact touches; its point is the mean of their centres. The loop's side is the direction
//! from the braid's point to the loop's, across the pull: an inversion turns it by about π in
//! the time of a snap.

use glam::DVec3;

/// The loop's place against the braid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopSide {
    /// Bodies in the loop.
    pub bodies: usize,
    /// From the braid's point to the loop's, its part across the pull (cm).
    pub offset_cm: DVec3,
}

/// A self contact as the loop sees it: its spline parameters (u_a, u_b) and the midpoint of
/// its closest points (cm).
pub type ContactPoint = (f64, f64, DVec3);

/// The loop of the rod with body `centres` and self `contacts`, pulled along the unit vector
/// `axis`; `None` without contacts or without a body between them that none touches.
pub fn loop_side(centres: &[DVec3], contacts: &[ContactPoint], axis: DVec3) -> Option<LoopSide> {
    let mut touched = vec![false; centres.len()];
    for &(u_a, u_b, _) in contacts {
        for u in [u_a, u_b] {
            // The spline's segment ⌊u⌋ blends bodies ⌊u⌋ − 1 … ⌊u⌋ + 2.
            let segment = u.floor() as usize;
            let end = (segment + 3).min(centres.len());
            touched[segment.saturating_sub(1)..end].iter_mut().for_each(|t| *t = true);
        }
    }
    let first = touched.iter().position(|&t| t)?;
    let last = touched.iter().rposition(|&t| t)?;
    let (mut best, mut start) = (first..first, None);
    for (k, &t) in touched.iter().enumerate().take(last + 1).skip(first) {
        match (t, start) {
            (false, None) => start = Some(k),
            (true, Some(s)) => {
                if k - s > best.len() {
                    best = s..k;
                }
                start = None;
            }
            _ => {}
        }
    }
    if best.is_empty() {
        return None;
    }
    let loop_point = centres[best.clone()].iter().sum::<DVec3>() / best.len() as f64;
    let braid_point = contacts.iter().map(|c| c.2).sum::<DVec3>() / contacts.len() as f64;
    let offset = loop_point - braid_point;
    Some(LoopSide { bodies: best.len(), offset_cm: offset - offset.dot(axis) * axis })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight strand with its middle bent into a ring above it (+z): the two strands
    /// touch where the ring closes; the loop is the ring, above the braid.
    #[test]
    fn the_loop_of_a_ring_lies_on_the_ring_s_side() {
        let mut centres: Vec<DVec3> = (0..20).map(|k| DVec3::new(f64::from(k), 0.0, 0.0)).collect();
        let ring = (0..24).map(|k| {
            let angle = std::f64::consts::TAU * f64::from(k) / 24.0;
            DVec3::new(
                20.0 + 3.0 * angle.sin(),
                0.3 * angle / std::f64::consts::TAU,
                3.0 - 3.0 * angle.cos(),
            )
        });
        centres.extend(ring);
        centres.extend((0..20).map(|k| DVec3::new(20.5 + f64::from(k), 0.3, 0.0)));
        let contact = (20.0, 44.0, 0.5 * (centres[20] + centres[44]));
        let side = loop_side(&centres, &[contact], DVec3::X).expect("a loop");
        assert_eq!(side.bodies, 44 - 1 - (20 + 3), "bodies 23 … 42");
        assert!(side.offset_cm.z > 2.5 && side.offset_cm.x == 0.0, "{side:?}");
        assert!(loop_side(&centres, &[], DVec3::X).is_none());
    }
}
