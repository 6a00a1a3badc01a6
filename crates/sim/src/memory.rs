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
//! n × m and m × m (W, its sorted copy, the active set's factor) for the m rows present (reserved for [`crate::step_data::row_reserve`]
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
        // Rows, Y and its sorted copy (n × m); W, its sorted copy and the active set's
        // factor of the free rows (m × m).
        DynamicsBackend::SparseMaximal => 3 * n * m + 3 * m * m,
    };
    let linear = (model.body_count() as u64).saturating_mul(BYTES_PER_BODY);
    matrices.saturating_mul(8).saturating_add(linear)
}

/// Which bound on the process' memory an estimate was checked against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MemoryBound {
    /// `MemAvailable` of `/proc/meminfo`: the machine's memory available without swapping.
    MachineAvailable,
    /// The address-space limit `RLIMIT_AS` (`ulimit -v`), less the address space in use
    /// (`VmSize`).
    AddressSpaceLimit,
    /// The data-segment limit `RLIMIT_DATA` (`ulimit -d`), less the data in use (`VmData`).
    DataLimit,
    /// The cgroup v2 `memory.max` of the process' cgroup, less its `memory.current`.
    CgroupMax,
    /// The cgroup v1 `memory.limit_in_bytes` of the process' memory cgroup, less its
    /// `memory.usage_in_bytes`.
    CgroupV1Limit,
}

impl std::fmt::Display for MemoryBound {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::MachineAvailable => "the machine's available memory (MemAvailable)",
            Self::AddressSpaceLimit => {
                "the process' address-space limit (RLIMIT_AS, `ulimit -v`) less what it maps"
            }
            Self::DataLimit => "the process' data limit (RLIMIT_DATA, `ulimit -d`) less its data",
            Self::CgroupMax => "its cgroup's memory.max less memory.current",
            Self::CgroupV1Limit => {
                "its memory cgroup's memory.limit_in_bytes less memory.usage_in_bytes (v1)"
            }
        })
    }
}

/// The memory a process may still allocate (bytes) under one bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryHeadroom {
    /// Bytes that may still be allocated.
    pub bytes: u64,
    /// The bound that gives them.
    pub bound: MemoryBound,
}

/// The memory available for new allocations: the smallest headroom under `MemAvailable`, the
/// process' `RLIMIT_AS` and `RLIMIT_DATA` (each less what is in use, `VmSize` and `VmData` of
/// `/proc/self/status`) and its cgroup's limit — v2 `memory.max` less `memory.current`, v1
/// `memory.limit_in_bytes` less `memory.usage_in_bytes` — those that can be read and are
/// finite; `None` if none is (then no check is made).
pub fn available_memory() -> Option<MemoryHeadroom> {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let status = read("/proc/self/status");
    let in_use = |field| status.as_deref().and_then(|s| status_kib(s, field));
    let limits = process_limits();
    let proc_cgroup = read("/proc/self/cgroup");
    let cgroup_limit = |dir: Option<String>, limit: &str, usage: &str| {
        let dir = dir?;
        let max = parse_cgroup_bytes(&read(&format!("{dir}/{limit}"))?)?;
        let current = read(&format!("{dir}/{usage}")).and_then(|t| parse_cgroup_bytes(&t));
        Some((max, current.unwrap_or(0)))
    };
    let v2 = proc_cgroup.as_deref().and_then(cgroup_v2_dir);
    let cgroup = cgroup_limit(v2, "memory.max", "memory.current");
    let v1 = proc_cgroup.as_deref().and_then(cgroup_v1_memory_dir);
    let cgroup_v1 = cgroup_limit(v1, "memory.limit_in_bytes", "memory.usage_in_bytes");
    let candidates = [
        read("/proc/meminfo")
            .and_then(|text| meminfo_available(&text))
            .map(|bytes| (bytes, 0, MemoryBound::MachineAvailable)),
        limits
            .address_space
            .map(|limit| (limit, in_use("VmSize:").unwrap_or(0), MemoryBound::AddressSpaceLimit)),
        limits.data.map(|limit| (limit, in_use("VmData:").unwrap_or(0), MemoryBound::DataLimit)),
        cgroup.map(|(max, current)| (max, current, MemoryBound::CgroupMax)),
        cgroup_v1.map(|(max, current)| (max, current, MemoryBound::CgroupV1Limit)),
    ];
    smallest_headroom(candidates.into_iter().flatten())
}

/// The smallest `limit − used` (saturating at 0) of `candidates` (limit, used, bound).
fn smallest_headroom(
    candidates: impl Iterator<Item = (u64, u64, MemoryBound)>,
) -> Option<MemoryHeadroom> {
    candidates
        .map(|(limit, used, bound)| MemoryHeadroom { bytes: limit.saturating_sub(used), bound })
        .min_by_key(|headroom| headroom.bytes)
}

/// The process' soft limits on its address space and data (bytes), `None` where unlimited.
#[derive(Debug, Clone, Copy, Default)]
struct ProcessLimits {
    address_space: Option<u64>,
    data: Option<u64>,
}

#[cfg(unix)]
fn process_limits() -> ProcessLimits {
    use rustix::process::{Resource, getrlimit};
    ProcessLimits {
        address_space: getrlimit(Resource::As).current,
        data: getrlimit(Resource::Data).current,
    }
}

#[cfg(not(unix))]
fn process_limits() -> ProcessLimits {
    ProcessLimits::default()
}

/// `MemAvailable` of a `/proc/meminfo` text, in bytes.
fn meminfo_available(meminfo: &str) -> Option<u64> {
    status_kib(meminfo, "MemAvailable:")
}

/// The value of the line starting with `field` of a `/proc/meminfo` or `/proc/self/status`
/// text (`VmSize:   3060 kB`), in bytes.
fn status_kib(text: &str, field: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(field))?;
    let kib: u64 = line[field.len()..].split_whitespace().next()?.parse().ok()?;
    kib.checked_mul(1024)
}

/// The directory of the process' cgroup v2 from a `/proc/self/cgroup` text: the path of its
/// `0::PATH` line under `/sys/fs/cgroup`; `None` without one (cgroup v1 only).
fn cgroup_v2_dir(proc_cgroup: &str) -> Option<String> {
    let path = proc_cgroup.lines().find_map(|l| l.strip_prefix("0::"))?.trim();
    let path = path.trim_end_matches('/');
    (!path.contains("..")).then(|| format!("/sys/fs/cgroup{path}"))
}

/// The directory of the process' cgroup v1 memory controller from a `/proc/self/cgroup` text:
/// the path of the `ID:CONTROLLERS:PATH` line whose controllers include `memory`, under
/// `/sys/fs/cgroup/memory`; `None` without one (cgroup v2 only).
fn cgroup_v1_memory_dir(proc_cgroup: &str) -> Option<String> {
    let path = proc_cgroup.lines().find_map(|line| {
        let mut parts = line.splitn(3, ':');
        let (_, controllers, path) = (parts.next()?, parts.next()?, parts.next()?);
        controllers.split(',').any(|c| c == "memory").then_some(path)
    })?;
    let path = path.trim().trim_end_matches('/');
    (!path.contains("..")).then(|| format!("/sys/fs/cgroup/memory{path}"))
}

/// A cgroup v2 `memory.max` or `memory.current` value in bytes; `None` for `max` (no limit)
/// or anything not a number.
fn parse_cgroup_bytes(text: &str) -> Option<u64> {
    text.trim().parse().ok()
}

/// Refuses `model` on `backend` if its step buffers would not fit in the memory it may still
/// allocate ([`available_memory`]).
///
/// # Errors
/// [`SimError::InsufficientMemory`] with the estimate, what is available and under which
/// bound.
pub fn check_memory(model: &Model, backend: DynamicsBackend) -> Result<(), SimError> {
    let needed = step_memory_estimate(model, backend);
    match available_memory() {
        Some(available) if needed > available.bytes => Err(SimError::InsufficientMemory {
            bodies: model.body_count(),
            dofs: model.dof_count(),
            needed,
            available: available.bytes,
            bound: available.bound,
            growth: match backend {
                DynamicsBackend::DenseReduced => "as the square of the DOFs",
                DynamicsBackend::SparseMaximal => "linearly in the bodies",
            },
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

    #[test]
    fn proc_texts_are_read_in_bytes() {
        let meminfo =
            "MemTotal:       24000000 kB\nMemFree:  100 kB\nMemAvailable:   22000000 kB\n";
        assert_eq!(meminfo_available(meminfo), Some(22_000_000 * 1024));
        assert_eq!(meminfo_available("MemTotal: 5 kB\n"), None);
        let status =
            "Name:\thagfish\nVmPeak:\t    3060 kB\nVmSize:\t    3000 kB\nVmData:\t 360 kB\n";
        assert_eq!(status_kib(status, "VmSize:"), Some(3000 * 1024));
        assert_eq!(status_kib(status, "VmData:"), Some(360 * 1024));
        assert_eq!(status_kib("VmSize:\t lots kB\n", "VmSize:"), None);
    }

    #[test]
    fn the_cgroup_v2_directory_and_limits_are_parsed() {
        let v1_and_v2 = "4:memory:/process_api/fa6f\n1:cpu:/\n0::/user.slice/run.scope\n";
        assert_eq!(
            cgroup_v2_dir(v1_and_v2).as_deref(),
            Some("/sys/fs/cgroup/user.slice/run.scope")
        );
        assert_eq!(cgroup_v2_dir("0::/\n").as_deref(), Some("/sys/fs/cgroup"));
        assert_eq!(cgroup_v2_dir("4:memory:/a\n"), None, "cgroup v1 only");
        assert_eq!(cgroup_v2_dir("0::/../../etc\n"), None);
        let v1 = "12:cpu,cpuacct:/x\n4:memory:/docker/abc/\n0::/\n";
        assert_eq!(cgroup_v1_memory_dir(v1).as_deref(), Some("/sys/fs/cgroup/memory/docker/abc"));
        assert_eq!(
            cgroup_v1_memory_dir("7:blkio,memory:/\n").as_deref(),
            Some("/sys/fs/cgroup/memory")
        );
        assert_eq!(cgroup_v1_memory_dir("0::/user.slice\n"), None, "cgroup v2 only");
        assert_eq!(cgroup_v1_memory_dir("4:memory:/../x\n"), None);
        assert_eq!(parse_cgroup_bytes("max\n"), None, "no limit");
        assert_eq!(parse_cgroup_bytes("1073741824\n"), Some(1 << 30));
    }

    #[test]
    fn the_smallest_headroom_wins_and_names_its_bound() {
        let candidates = [
            (8 << 30, 0, MemoryBound::MachineAvailable),
            (1 << 30, 200 << 20, MemoryBound::AddressSpaceLimit),
            (2 << 30, 10 << 20, MemoryBound::DataLimit),
        ];
        let smallest = smallest_headroom(candidates.into_iter()).expect("a bound");
        assert_eq!(
            smallest,
            MemoryHeadroom {
                bytes: (1 << 30) - (200 << 20),
                bound: MemoryBound::AddressSpaceLimit
            }
        );
        let exhausted = [
            (1 << 20, 2 << 20, MemoryBound::CgroupMax),
            (1 << 30, 0, MemoryBound::MachineAvailable),
        ];
        assert_eq!(
            smallest_headroom(exhausted.into_iter()).map(|h| (h.bytes, h.bound)),
            Some((0, MemoryBound::CgroupMax))
        );
        assert_eq!(smallest_headroom(std::iter::empty()), None);
    }

    #[test]
    fn this_process_has_a_headroom_no_larger_than_its_machine_memory() {
        let headroom = available_memory().expect("Linux has /proc/meminfo");
        let machine =
            std::fs::read_to_string("/proc/meminfo").ok().and_then(|t| meminfo_available(&t));
        assert!(headroom.bytes <= machine.expect("MemAvailable"), "{headroom:?}");
    }
}
