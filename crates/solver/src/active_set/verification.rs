//! Verification of the active set against the refined answer (step 5 of the method).
//!
//! The dual gradient of a bound row, gᵢ = (Wλ)ᵢ − rᵢ, is rounded like Σⱼ|Wᵢⱼλⱼ|, which is
//! pessimistic when large multipliers cancel; the refined primal residual cᵢᵀq̇ − bᵢ is exact
//! to the rounding of the row itself, relative to sᵢ = 1 + |bᵢ| + Σⱼ|cᵢⱼq̇ⱼ|. So after
//! refinement:
//!
//! - a bound row violated beyond τ·sᵢ (τ = `release_tolerance`) is released and the
//!   iteration resumed from the current working set;
//! - an equality set aside as redundant (dependent on the other equalities) must hold:
//!   violated beyond the acceptance, the equalities contradict each other.

use super::{ActiveSet, ActiveSetLimits, ActiveSetOutcome, Bound, Termination};
use crate::contact_space::ContactSpace;

impl ActiveSet {
    /// Continues after the primal verification found a bound row violated: releases it and
    /// iterates again from the current working set.
    pub(crate) fn resume(
        &mut self,
        dual: &ContactSpace,
        lambda: &mut [f64],
        limits: ActiveSetLimits,
        row: usize,
    ) -> ActiveSetOutcome {
        if !self.release(dual, lambda, row) {
            return ActiveSetOutcome { iterations: 0, termination: Termination::Infeasible };
        }
        self.iterate(dual, lambda, limits)
    }

    /// The bound row most violated in the primal at the refined q̇ (relative residual beyond
    /// `tolerance`), if any (see the module docs); `residuals` are the rows' (vᵢ, sᵢ) at q̇
    /// (`residuals::row_residuals`).
    pub(crate) fn violated_bound(&self, residuals: &[(f64, f64)], tolerance: f64) -> Option<usize> {
        let mut worst: Option<(usize, f64)> = None;
        for (row, (bound, &(residual, scale))) in self.bound.iter().zip(residuals).enumerate() {
            let violation = match bound {
                Bound::Lower => -residual / scale,
                Bound::Upper => residual / scale,
                Bound::Free | Bound::Redundant => continue,
            };
            if violation > tolerance && worst.is_none_or(|(_, top)| violation > top) {
                worst = Some((row, violation));
            }
        }
        worst.map(|(found, _)| found)
    }

    /// True when an equality set aside as redundant is violated at the refined q̇ (relative
    /// residual beyond `tolerance`): the equalities contradict each other. `residuals` as
    /// for [`violated_bound`](Self::violated_bound).
    pub(crate) fn redundant_violated(&self, residuals: &[(f64, f64)], tolerance: f64) -> bool {
        self.bound
            .iter()
            .zip(residuals)
            .any(|(bound, &(v, scale))| *bound == Bound::Redundant && v.abs() > tolerance * scale)
    }
}
