//! The memory a world's step buffers need, estimated before they are allocated, so that a body
//! too large for the machine is refused with an error instead of an allocation failure.
//!
//! The step's buffers are dense in the DOF count n (both backends, for now): the tree's M, M̃ and
//! its factor, the same three in the contact predictor's kinematics, the rows (n × m with a row
//! capacity m = 2n), and the contact-space solve's Y and its sorted copy (n × m each), W and
//! its sorted copy (m × m each): 3 + 3 + 2 + 2 + 2 + 4 + 4 = 20 n² doubles = 160 n² bytes. The
//! resident size measured at 1000 and 2000 bodies was 0.65 of that (not every reserved page is
//! touched), so the estimate is an upper bound: ES103 with 100 bodies needs 3.6 MB, 1000 bodies
//! 360 MB, 10 000 bodies 36 GB.

use hagfish_tree::Model;

use crate::error::SimError;

/// Doubles per n² of the step buffers (see the module documentation).
const DOUBLES_PER_DOF_SQUARED: u64 = 20;

/// Bytes per body of everything linear in the body count (frames, twists, contact buffers,
/// spline samples): a generous bound, 64 KiB.
const BYTES_PER_BODY: u64 = 64 * 1024;

/// The bytes the step buffers of `model` need (an upper bound).
pub fn step_memory_estimate(model: &Model) -> u64 {
    let n = model.dof_count() as u64;
    let dense = n.saturating_mul(n).saturating_mul(DOUBLES_PER_DOF_SQUARED * 8);
    dense.saturating_add((model.body_count() as u64).saturating_mul(BYTES_PER_BODY))
}

/// The memory available for new allocations (bytes): `MemAvailable` of `/proc/meminfo` on
/// Linux; `None` where it cannot be read (then no check is made).
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// Refuses `model` if its step buffers would not fit in the available memory.
///
/// # Errors
/// [`SimError::InsufficientMemory`] with the estimate and what is available.
pub fn check_memory(model: &Model) -> Result<(), SimError> {
    let needed = step_memory_estimate(model);
    match available_memory() {
        Some(available) if needed > available => Err(SimError::InsufficientMemory {
            bodies: model.body_count(),
            dofs: model.dof_count(),
            needed,
            available,
        }),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimate_grows_with_the_square_of_the_dofs() {
        let chain = |bodies| crate::segment_chain(bodies).expect("chain");
        let (small, large) =
            (step_memory_estimate(&chain(100)), step_memory_estimate(&chain(1000)));
        let n = chain(100).dof_count() as u64;
        assert_eq!(small, 160 * n * n + 100 * BYTES_PER_BODY);
        assert!(large > 99 * small && large < 101 * small, "{small} → {large}");
    }
}
