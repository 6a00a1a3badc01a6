//! The memory a world's step buffers need, estimated before they are allocated, so that a body
//! too large for the machine is refused with an error instead of an allocation failure.
//!
//! **Dense backend**: the buffers are dense in the DOF count n — the tree's M̃ and
//! its factor (M only if asked for), the rows (n × m with a row capacity m = 2n), and the
//! contact-space solve's Y and its sorted copy (n × m each), W and its sorted copy (m × m each),
//! and the solver's own factor of M̃: 2 + 2 + 2 + 2 + 4 + 4 + 1 = 17, counted as 20 n² doubles
//! = 160 n² bytes. The resident size measured at 1000 and 2000 bodies was 0.65 of that (not
//! every reserved page is touched), so it is an upper bound: ES103 with 100 bodies needs
//! 3.6 MB, 1000 bodies 360 MB, 10 000 bodies 36 GB.
//!
//! **Sparse backend** (the default): nothing is n × n. The rows and contact-space matrices are
//! n × m and m × m for the m rows present (reserved for [`crate::step_data::row_reserve`]
//! rows, growing when a step has more), and everything else is linear in the bodies.

use hagfish_tree::Model;

use crate::backend::DynamicsBackend;
use crate::error::SimError;
use crate::step_data::row_reserve;

/// Doubles per n² of the dense backend's step buffers (see the module documentation).
const DOUBLES_PER_DOF_SQUARED: u64 = 20;

/// Bytes per body of everything linear in the body count (frames, twists, contact buffers,
/// spline samples, the sparse factor's blocks): a generous bound, 64 KiB.
const BYTES_PER_BODY: u64 = 64 * 1024;

/// The bytes the step buffers of `model` need on `backend` (an upper bound for the dense
/// backend; for the sparse one, at the reserved row count).
pub fn step_memory_estimate(model: &Model, backend: DynamicsBackend) -> u64 {
    let n = model.dof_count() as u64;
    let m = row_reserve(model, backend) as u64;
    let matrices = match backend {
        DynamicsBackend::DenseReduced => {
            n.saturating_mul(n).saturating_mul(DOUBLES_PER_DOF_SQUARED)
        }
        // Rows, Y and its sorted copy (n × m); W and its sorted copy (m × m).
        DynamicsBackend::SparseMaximal => 3 * n * m + 2 * m * m,
    };
    let linear = (model.body_count() as u64).saturating_mul(BYTES_PER_BODY);
    matrices.saturating_mul(8).saturating_add(linear)
}

/// The memory available for new allocations (bytes): `MemAvailable` of `/proc/meminfo` on
/// Linux; `None` where it cannot be read (then no check is made).
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// Refuses `model` on `backend` if its step buffers would not fit in the available memory.
///
/// # Errors
/// [`SimError::InsufficientMemory`] with the estimate and what is available.
pub fn check_memory(model: &Model, backend: DynamicsBackend) -> Result<(), SimError> {
    let needed = step_memory_estimate(model, backend);
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
    fn the_dense_estimate_grows_with_the_square_and_the_sparse_one_linearly() {
        let chain = |bodies| hagfish_anatomy::segment_chain(bodies).expect("chain");
        let dense = |bodies| step_memory_estimate(&chain(bodies), DynamicsBackend::DenseReduced);
        let sparse = |bodies| step_memory_estimate(&chain(bodies), DynamicsBackend::SparseMaximal);
        let n = chain(100).dof_count() as u64;
        assert_eq!(dense(100), 160 * n * n + 100 * BYTES_PER_BODY);
        let quadratic = |bodies: u64| dense(bodies as usize) - bodies * BYTES_PER_BODY;
        assert_eq!(quadratic(1000), 100 * quadratic(100));
        assert!(sparse(10_000) <= 10 * sparse(1000) && sparse(10_000) > 9 * sparse(1000));
    }
}
