//! Friction at a contact (docs/physics.md, "Friction: the cone and its pyramid"): the rows of
//! a contact push along the edges of its friction cone's inscribed pyramid instead of along
//! the normal alone.
//!
//! With unit normal n̂ and tangents t̂₁ (the reference direction made normal to n̂) and
//! t̂₂ = n̂ × t̂₁, edge k pushes along dₖ = n̂ + μ(cos θₖ t̂₁ + sin θₖ t̂₂), θₖ = 2πk/E: its row is
//! the contact's normal row with n̂ replaced by dₖ and the same right-hand side (the tangent
//! targets are 0, the surfaces being still). Its multiplier βₖ ≥ 0; the contact's impulse is
//! λ_n = Σβₖ along n̂ and μΣβₖ(cos θₖ, sin θₖ) along the tangents, inside Coulomb's cone and
//! short of it by at most 1 − cos(π/E).
//!
//! The exact cone ([`ConeForm::Exact`], the reference) writes the contact's normal row and two
//! friction rows along t̂₁ and t̂₂ (target 0) instead, which the clarabel backend solves as one
//! second-order cone (`hagfish_solver::RowKind::Friction`).

use glam::DVec3;
use hagfish_solver::{FrictionPyramid, RowKind, Rows};
use serde::{Deserialize, Serialize};

use super::stabilisation::unilateral_rhs;
use crate::error::SimError;

/// Most edges of a pyramid (the directions of one contact live in a fixed array).
pub const MAX_FRICTION_EDGES: usize = 16;

/// Coulomb friction on the self contacts and the wall (static = kinetic).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Friction {
    /// μ, finite and ≥ 0.
    pub coefficient: f64,
    /// Edges E of the inscribed pyramid, 3 ≤ E ≤ [`MAX_FRICTION_EDGES`] (default 8: the
    /// friction limit within 7.6 % of Coulomb's in every direction).
    #[serde(default = "default_edges")]
    pub edges: usize,
    /// How the cone is written into the rows (default [`ConeForm::Pyramid`]).
    #[serde(default)]
    pub cone: ConeForm,
}

/// How a contact's friction cone is written into its rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum ConeForm {
    /// Its inscribed pyramid of `edges` edges: plain inequality rows, for any backend (the
    /// fast path).
    #[default]
    Pyramid,
    /// Exactly: the normal row and two friction rows, a second-order cone that only the
    /// clarabel backend solves (the reference, 7–40 ms a solve on the hagfish).
    Exact,
}

fn default_edges() -> usize {
    8
}

impl Friction {
    /// The inscribed pyramid of `edges` edges at coefficient μ.
    pub fn pyramid(coefficient: f64, edges: usize) -> Self {
        Friction { coefficient, edges, cone: ConeForm::Pyramid }
    }

    /// The exact cone at coefficient μ (the clarabel backend only).
    pub fn exact(coefficient: f64) -> Self {
        Friction { coefficient, edges: default_edges(), cone: ConeForm::Exact }
    }

    /// Checks μ and the number of edges.
    pub fn validate(&self) -> Result<(), SimError> {
        let mu = self.coefficient;
        if !(mu.is_finite() && mu >= 0.0) {
            let expected = "finite and ≥ 0";
            return Err(SimError::InvalidOption {
                name: "friction.coefficient",
                value: mu,
                expected,
            });
        }
        if !(3..=MAX_FRICTION_EDGES).contains(&self.edges) {
            let (name, value) = ("friction.edges", self.edges as f64);
            return Err(SimError::InvalidOption { name, value, expected: "3 to 16" });
        }
        Ok(())
    }
}

/// The directions along which a contact's rows push, into `out`; returns how many: n̂ alone
/// without friction (`None` or μ = 0, so that such runs are the frictionless ones bit for
/// bit), else the pyramid's E edges about n̂, or for the exact cone n̂, t̂₁ and t̂₂; t̂₁ is
/// `reference` made normal to n̂ (another direction is taken if it is along n̂).
pub fn contact_directions(
    normal: DVec3,
    reference: DVec3,
    friction: Option<Friction>,
    out: &mut [DVec3; MAX_FRICTION_EDGES],
) -> usize {
    let Some(friction) = friction.filter(|f| f.coefficient > 0.0) else {
        out[0] = normal;
        return 1;
    };
    let first = (reference - normal * reference.dot(normal))
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    let second = normal.cross(first);
    if friction.cone == ConeForm::Exact {
        out[..3].copy_from_slice(&[normal, first, second]);
        return 3;
    }
    let pyramid = FrictionPyramid {
        coefficient: friction.coefficient,
        edges: friction.edges,
        first_angle: 0.0,
    };
    for (k, direction) in out.iter_mut().enumerate().take(friction.edges) {
        let (c, s) = pyramid.direction(k);
        *direction = normal + friction.coefficient * (c * first + s * second);
    }
    friction.edges
}

/// The kind and bound of row `k` of a contact's rows, the first of which is row `first` of
/// the rows: a unilateral row on the contact's `gap` ([`unilateral_rhs`]) for the normal and
/// for every edge of a pyramid, or with the exact cone (k = 1, 2) a friction row of the cone
/// whose normal row is `first`, target 0. On a moving surface the row bounds the velocity
/// relative to it: `surface_speed` (the row's direction · the surface's velocity) is added to
/// the bound (zero adds nothing, bit for bit).
pub(super) fn contact_row(
    (gap, surface_speed): (f64, f64),
    (time_step, push_out): (f64, f64),
    friction: Option<Friction>,
    (k, first): (usize, usize),
) -> (RowKind, f64) {
    let (kind, target) = match friction {
        Some(Friction { coefficient, cone: ConeForm::Exact, .. }) if k > 0 => {
            (RowKind::Friction { normal: first, coefficient }, 0.0)
        }
        _ => (RowKind::Inequality, unilateral_rhs(gap, time_step, push_out)),
    };
    let rhs = if surface_speed == 0.0 { target } else { target + surface_speed };
    (kind, rhs)
}

/// The three base rows of a contact whose `edges` rows run along the edges of a friction
/// pyramid, or `None` (frictionless, or the exact cone: one row per direction already): each
/// edge row `dᵀG` is then `Σₖ d_k g_k` with `g_k` the row along world axis k, which `fill`
/// writes, given the three axes and their rows (`Rows::push_combination`), so that the
/// contact-space build solves for three rows instead of `edges`.
pub(super) fn push_pyramid_bases(
    rows: &mut Rows,
    friction: Option<Friction>,
    edges: usize,
    fill: impl FnOnce([DVec3; 3], [&mut [f64]; 3]),
) -> Option<usize> {
    let pyramid = friction.is_some_and(|f| f.cone == ConeForm::Pyramid);
    if !pyramid || edges < 2 {
        return None;
    }
    let first = rows.push_bases();
    fill([DVec3::X, DVec3::Y, DVec3::Z], rows.bases_mut(first));
    Some(first)
}

/// Where a wall (or obstacle) contact's rows act, as an offset from the body's centre: the
/// centre itself along the normal alone (`edges` = 1; the rows as they were without friction),
/// else the contact point c − r n̂, whose tangential velocity the body's spin moves.
pub fn wall_contact_offset(edges: usize, radius: f64, normal: DVec3) -> DVec3 {
    if edges == 1 { DVec3::ZERO } else { -radius * normal }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_edges_tilt_the_normal_by_mu_around_it() {
        let mut out = [DVec3::ZERO; MAX_FRICTION_EDGES];
        let n = DVec3::Z;
        assert_eq!(contact_directions(n, DVec3::X, None, &mut out), 1);
        assert_eq!(out[0], n);
        let off = Friction::pyramid(0.0, 8);
        assert_eq!(contact_directions(n, DVec3::X, Some(off), &mut out), 1);
        let friction = Friction::pyramid(0.3, 8);
        assert_eq!(contact_directions(n, DVec3::new(1.0, 0.0, 0.4), Some(friction), &mut out), 8);
        for d in &out[..8] {
            assert!((d.dot(n) - 1.0).abs() < 1e-15, "the normal part is n̂");
            assert!(((*d - n).length() - 0.3).abs() < 1e-15, "the tangential part is μ");
        }
        assert!((out[0] - (n + 0.3 * DVec3::X)).length() < 1e-15, "the first edge along t̂₁");
        // A reference along the normal still gives a tangent frame.
        assert_eq!(contact_directions(n, n, Some(friction), &mut out), 8);
        assert!(out[..8].iter().all(|d| ((*d - n).length() - 0.3).abs() < 1e-15));
    }

    #[test]
    fn bad_friction_is_refused_with_its_field() {
        for (friction, name) in [
            (Friction::pyramid(-0.1, 8), "friction.coefficient"),
            (Friction::pyramid(f64::NAN, 8), "friction.coefficient"),
            (Friction::pyramid(0.1, 2), "friction.edges"),
            (Friction::pyramid(0.1, 17), "friction.edges"),
        ] {
            let refused = friction.validate();
            assert!(matches!(refused, Err(SimError::InvalidOption { name: n, .. }) if n == name));
        }
    }
}
