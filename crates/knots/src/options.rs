//! Options of the knot analysis.

use crate::KnotError;

/// How thoroughly [`crate::analyse_knot`] samples closure directions.
///
/// The analysis is deterministic (no seed): directions come from a Fibonacci sphere, so
/// equal inputs and options give bit-identical reports.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KnotOptions {
    /// Number of closure directions voting on the knot type (≥ 1; default 64). The cost is
    /// linear in it.
    pub directions: usize,
    /// Whether to locate the knotted sub-arc ([`crate::KnotReport::extent`]); this costs
    /// about 2 log₂(n) extra votes with [`KnotOptions::extent_directions`] directions each.
    pub extent: bool,
    /// Number of closure directions of each vote during the extent search (≥ 1; default 16).
    pub extent_directions: usize,
}

impl Default for KnotOptions {
    fn default() -> Self {
        Self { directions: 64, extent: true, extent_directions: 16 }
    }
}

impl KnotOptions {
    /// Checks the ranges documented on the fields.
    pub(crate) fn validate(&self) -> Result<(), KnotError> {
        KnotError::require_option(
            self.directions >= 1,
            "directions",
            "at least 1",
            self.directions,
        )?;
        KnotError::require_option(
            self.extent_directions >= 1,
            "extent_directions",
            "at least 1",
            self.extent_directions,
        )
    }
}
