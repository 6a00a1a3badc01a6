//! Releasing a row from its bound, with linearly dependent rows handled exactly.
//!
//! Row i leaves its bound in direction s = +1 (off a lower bound) or −1 (off an upper one)
//! because its dual gradient gᵢ = cᵢᵀq̇ − bᵢ has the wrong sign (s·gᵢ < 0). If cᵢ is
//! independent of c_F it simply joins F. Otherwise cᵢ ≈ Σ_p z_p c_p (a duplicated contact, a
//! limit row on a held DOF, or a degenerate vertex with more tight rows than DOFs) and
//! W_FF ∪ {i} would be (nearly) singular. Along d = s(eᵢ − Σ_p z_p e_p)
//!
//! φ(λ + t·d) = φ(λ) + t·ν + ½κt²,  κ = dᵀWd = the pivot of cᵢ against F,
//!
//! with the rate ν = gᵀd, computed in the primal rather than from the rounded gradients
//! (which at a degenerate vertex are pure rounding):
//!
//! ν = (Σ dⱼ L⁻¹cⱼ)ᵀ(z + Yλ) + dᵀEλ − s·ρ,  ρ = bᵢ − Σ_p z_p b_p,
//!
//! i.e. (Σ dⱼcⱼ)ᵀq̇ + dᵀEλ − dᵀb; the first term vanishes for an exact dependence, the second
//! but for compliant rows (E their compliances, which keep them independent in W).
//!
//! - ν not significantly negative (`CONSISTENCY`): the release was rounding; the row is
//!   implied by F and skipped until F changes.
//! - Near dependence (κ above rounding): φ bottoms out at t* = −ν/κ; if that comes before any
//!   bound, the row joins F like an independent one.
//! - Otherwise step along d until a bound blocks (Harris two-pass ratio test: bounds relaxed
//!   by `HARRIS` to find the step, then the blocking row with the largest |z_p| among those
//!   reached, which keeps the new pivot large; rows overshooting by less than the relaxation
//!   are clamped). The blocked row leaves F and i takes its place, so F stays independent and
//!   φ strictly falls (no cycling between near-parallel rows). The new pivot is
//!   z_p²·(pivot of c_p against the rest of F): it may be tiny against W_ii (rows of sizes
//!   100 apart, z_p = 5.5e-5 gave 8e-14·W_ii, and the true multipliers were 5e7) and is
//!   accepted when it matches that product to `AGREEMENT`. Should i still be dependent after
//!   the swap (z_p rounding noise) the step is undone and i skipped. If λᵢ's own other bound
//!   (a soft weight) comes first, it moves there.
//! - Nothing blocks (exact dependence, every inequality z_p ≤ 0): φ is unbounded below and d
//!   is a Farkas ray (Σ dⱼcⱼ ≈ 0, dᵀb = s·ρ > 0, d ≥ 0 on inequalities), so the hard rows are
//!   infeasible — once the ray excludes every q̇ of M̃-norm up to `RADIUS` times the current
//!   one (a feasible q̇ would give dᵀb ≤ ‖Σ dⱼL⁻¹cⱼ‖·‖q̇‖_M; an ill-conditioned F can fake a
//!   ray through an inaccurate z, and the row is then skipped like an implied one).

use super::{ActiveSet, Bound, DEPENDENCE, Join, ROUNDING};
use crate::contact_space::ContactSpace;
use crate::linalg::{Entries, dot, zeroed};

/// The rate ν of a dependent release is significant beyond this fraction of the size of its
/// terms, |b_row| + Σ_p|z_p b_p| + ‖Σ dⱼL⁻¹cⱼ‖·‖z + Yλ‖.
const CONSISTENCY: f64 = 1e-9;

/// Harris relaxation of the bounds in the ratio test, relative to 1 + max_p |λ_p|.
const HARRIS: f64 = 1e-12;

/// A swapped-in row's pivot that is small against W_rr is real when it agrees with
/// z_p²·(pivot of c_p against the rest) to this relative tolerance.
const AGREEMENT: f64 = 0.1;

/// A Farkas ray must exclude every q̇ up to this many times the current ‖q̇‖_M.
const RADIUS: f64 = 1e3;

/// The rate of φ along the null direction d of a dependent release, and its parts.
#[derive(Debug, Clone, Copy)]
struct Rate {
    /// ν = gᵀd.
    value: f64,
    /// Size of the terms of ν, for its significance.
    scale: f64,
    /// ρ = b_row − Σ_p z_p b_p (dᵀb = s·ρ).
    rho: f64,
    /// ‖Σ dⱼL⁻¹cⱼ‖, zero for an exact dependence.
    ray: f64,
    /// ‖z + Yλ‖ = ‖q̇(λ)‖_M.
    size: f64,
}

/// Where a dependent release's step along d stops: the free row at `position` of F reaches
/// its `side` bound after the step `step`.
#[derive(Debug, Clone, Copy)]
struct Block {
    position: usize,
    side: Bound,
    step: f64,
}

/// What releasing a row did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Release {
    /// The row was independent of F and joined it; λ is unchanged.
    Joined,
    /// The row depended on F and was dealt with (skipped as implied, joined at φ's minimum
    /// along d, moved to its other bound or swapped in); λ may have moved.
    Resolved,
    /// φ is unbounded below: the hard rows are infeasible.
    Infeasible,
}

impl ActiveSet {
    /// Releases `row` from its bound (see the module docs).
    pub(super) fn release(
        &mut self,
        dual: &ContactSpace,
        lambda: &mut [f64],
        row: usize,
    ) -> Release {
        let s = if self.bound[row] == Bound::Lower { 1.0 } else { -1.0 };
        let Join::Dependent { pivot } = self.try_join(dual, row, DEPENDENCE) else {
            return Release::Joined;
        };
        let rate = self.dependent_rate(dual, lambda, row, s);
        if rate.value >= -CONSISTENCY * rate.scale {
            self.implied[row] = self.version;
            return Release::Resolved;
        }
        let minimum = if pivot > ROUNDING * dual.entry(row, row) {
            -rate.value / pivot
        } else {
            f64::INFINITY
        };
        let own =
            if s > 0.0 { self.upper[row] - lambda[row] } else { lambda[row] - self.lower[row] };
        let Some(block) = self.ratio_test(lambda, s) else {
            // No free row blocks.
            if minimum.min(own).is_finite() {
                self.settle(lambda, row, pivot, minimum, own);
                return Release::Resolved;
            }
            if s * rate.rho > rate.ray * RADIUS * (1.0 + rate.size) {
                return Release::Infeasible;
            }
            self.implied[row] = self.version;
            return Release::Resolved;
        };
        if minimum.min(own) <= block.step {
            self.settle(lambda, row, pivot, minimum, own);
        } else {
            self.swap(dual, lambda, row, s, block);
        }
        Release::Resolved
    }

    /// The rate ν = (Σ dⱼL⁻¹cⱼ)ᵀ(z + Yλ) + dᵀEλ − s·ρ of φ along d (z in `self.z`), with its parts.
    fn dependent_rate(&mut self, dual: &ContactSpace, lambda: &[f64], row: usize, s: f64) -> Rate {
        let b = dual.b();
        let terms = self.z.iter().zip(self.free.indices()).map(|(z, &i)| z * b[i]);
        let (implied, data) =
            terms.fold((0.0, b[row].abs()), |(sum, size), t| (sum + t, size + t.abs()));
        let rho = b[row] - implied;
        zeroed(&mut self.lift, dual.dofs());
        dual.lift(lambda, &mut self.reduced, &mut self.lift);
        zeroed(&mut self.ray, dual.dofs());
        dual.y_axpy(row, s, &mut self.ray);
        for (&zp, &i) in self.z.iter().zip(self.free.indices()) {
            dual.y_axpy(i, -s * zp, &mut self.ray);
        }
        let (ray, size) = (dot(&self.ray, &self.ray).sqrt(), dot(&self.lift, &self.lift).sqrt());
        let e = dual.compliance();
        let springs = self.z.iter().zip(self.free.indices()).map(|(z, &i)| z * e[i] * lambda[i]);
        let (implied_spring, spring_size) = springs
            .fold((0.0, (e[row] * lambda[row]).abs()), |(sum, size), t| (sum + t, size + t.abs()));
        let spring = s * (e[row] * lambda[row] - implied_spring);
        Rate {
            value: dot(&self.ray, &self.lift) + spring - s * rho,
            scale: data + spring_size + ray * size,
            rho,
            ray,
            size,
        }
    }

    /// Harris ratio test along d = s(e_row − Σ_p z_p e_p): the free row to swap out, or
    /// `None` when no free row blocks.
    fn ratio_test(&self, lambda: &[f64], s: f64) -> Option<Block> {
        let indices = self.free.indices();
        let scale = indices.iter().fold(1.0_f64, |a, &i| a.max(1.0 + lambda[i].abs()));
        let relaxation = HARRIS * scale;
        // Distance of λ_p to the bound it moves toward, and the speed |s·z_p| it moves at.
        let limit_of = |position: usize| {
            let (i, rate) = (indices[position], -s * self.z[position]);
            let (bound, side) = if rate < 0.0 {
                (self.lower[i], Bound::Lower)
            } else {
                (self.upper[i], Bound::Upper)
            };
            (rate != 0.0 && bound.is_finite())
                .then(|| (((bound - lambda[i]) / rate).max(0.0), rate.abs(), side))
        };
        let relaxed = (0..indices.len())
            .filter_map(|p| limit_of(p).map(|(t, speed, _)| t + relaxation / speed))
            .fold(f64::INFINITY, f64::min);
        (0..indices.len())
            .filter_map(|p| limit_of(p).map(|(t, _, side)| (p, t, side)))
            .filter(|&(_, t, _)| t <= relaxed)
            .max_by(|a, b| self.z[a.0].abs().total_cmp(&self.z[b.0].abs()).then(b.0.cmp(&a.0)))
            .map(|(position, step, side)| Block { position, side, step })
    }

    /// No free row blocks before φ's minimum along d or λ_row's own other bound: a nearly
    /// dependent row joins F (the next subproblem moves there), or λ_row moves to the bound.
    fn settle(&mut self, lambda: &mut [f64], row: usize, pivot: f64, minimum: f64, own: f64) {
        if minimum <= own {
            self.join(row, pivot);
            return;
        }
        let k = self.free.indices().len();
        let s = if self.bound[row] == Bound::Lower { 1.0 } else { -1.0 };
        for (&zp, &i) in self.z[..k].iter().zip(self.free.indices()) {
            lambda[i] -= s * own * zp;
        }
        let side = if s > 0.0 { Bound::Upper } else { Bound::Lower };
        self.fix(lambda, row, side);
    }

    /// A warm-started `row` that depends on F (c_row ≈ Σ_p z_p c_p, z in `self.z`) hands its
    /// impulse to the rows it depends on: λ moves along d = Σ_p z_p e_p − e_row, which keeps
    /// Cᵀλ up to the dependence, until λ_row reaches its lower bound, or a free row its bound
    /// first: that row then leaves F and `row` takes its place ([`Self::swap`]; should `row`
    /// still be dependent without it, `row` is left at its bound as it was).
    pub(super) fn hand_over(&mut self, dual: &ContactSpace, lambda: &mut [f64], row: usize) {
        let own = lambda[row] - self.lower[row];
        if let Some(block) = self.ratio_test(lambda, -1.0).filter(|block| block.step < own) {
            self.swap(dual, lambda, row, -1.0, block);
            if self.implied[row] != usize::MAX {
                self.fix(lambda, row, Bound::Lower);
            }
            return;
        }
        let k = self.free.indices().len();
        for (&zp, &i) in self.z[..k].iter().zip(self.free.indices()) {
            lambda[i] = (lambda[i] + own * zp).clamp(self.lower[i], self.upper[i]);
        }
        self.fix(lambda, row, Bound::Lower);
    }

    /// Steps along d to the block, swaps the blocked free row out of F and `row` in; undoes
    /// the step if `row` is still dependent without it.
    fn swap(&mut self, dual: &ContactSpace, lambda: &mut [f64], row: usize, s: f64, block: Block) {
        let Block { position, side, step } = block;
        let k = self.free.indices().len();
        self.saved.clear();
        self.saved.push((row, lambda[row]));
        self.saved.extend(self.free.indices().iter().map(|&i| (i, lambda[i])));
        lambda[row] += s * step;
        for (&zp, &i) in self.z[..k].iter().zip(self.free.indices()) {
            // Rows overshooting by less than the Harris relaxation are clamped to their box.
            lambda[i] = (lambda[i] - s * step * zp).clamp(self.lower[i], self.upper[i]);
        }
        let version = self.version;
        let zp = self.z[position];
        let blocked = self.free.remove(position);
        self.version += 1;
        // The span of c_F is unchanged and c_row = z_p c_p + (rows of the rest), so the new
        // pivot is z_p²·(the pivot of c_p against the rest): real when clear of rounding, or
        // when it matches that product (a z_p of rounding noise leaves a pivot that does not).
        let expected = zp * zp * self.free.border(dual, blocked, &mut self.border);
        let pivot = self.free.border(dual, row, &mut self.border);
        if pivot > ROUNDING * dual.entry(row, row)
            || (pivot - expected).abs() <= AGREEMENT * expected
        {
            self.join(row, pivot);
            self.fix(lambda, blocked, side);
            return;
        }
        for &(i, value) in &self.saved {
            lambda[i] = value;
        }
        if self.try_join(dual, blocked, ROUNDING) == Join::Joined {
            // F holds the same rows again: earlier "implied" marks stay valid.
            self.version = version;
        } else {
            self.fix(lambda, blocked, side);
        }
        self.implied[row] = self.version;
    }
}
