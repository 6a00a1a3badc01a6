//! Friction: the exact cone and its inscribed pyramid.
//!
//! A contact with normal row c_n (velocity v_n = c_nᵀq̇ − b_n) and tangent rows c_t1, c_t2
//! (slip v_t) under Anitescu's convex relaxation of Coulomb's law (the cone MuJoCo and the
//! thesis' peers use) has its impulse in the friction cone and its velocity in the dual cone,
//! complementary:
//!
//! ‖λ_t‖ ≤ μλ_n,   v_n ≥ μ‖v_t‖,   λ_n v_n + λ_t·v_t = 0.
//!
//! It is the minimum of the velocity QP with the contact's impulse confined to the cone, so it
//! is convex and unique in q̇. A sticking contact has v = 0; a sliding one the force
//! −μλ_n v_t/‖v_t‖ (maximal dissipation) and, unlike Coulomb's law, a normal velocity
//! v_n = μ‖v_t‖: the contact opens by hμ‖v_t‖ in a step while sliding (the price of the
//! convexity; the contact rows' speculative margin closes it again).
//!
//! - **Exact**: [`RowKind::Friction`] rows after their normal row; the clarabel backend solves
//!   the cone as a second-order cone (`clarabel_reference.rs`). The reference.
//! - **Fast**: the cone's inscribed pyramid of E edges, dₖ = (cos θₖ, sin θₖ), θₖ = θ₀ + 2πk/E:
//!   the impulse Σₖ βₖ(c_n + μ(cos θₖ c_t1 + sin θₖ c_t2)) with βₖ ≥ 0, i.e. E plain
//!   inequality rows eₖ = c_n + μ(cos θₖ c_t1 + sin θₖ c_t2), eₖᵀq̇ ≥ b_n (+ μ dₖ·b_t), which
//!   the contact-space active set solves exactly ([`FrictionPyramid`]). Then λ_n = Σβₖ and
//!   λ_t = μΣβₖdₖ. The pyramid lies inside the cone, its cross-section the regular E-gon
//!   inscribed in the disc: a friction limit between μ cos(π/E) λ_n (midway between two
//!   edges) and μλ_n (along an edge), so it never exceeds Coulomb's force and falls short of
//!   it by at most 1 − cos(π/E) (7.6 % at E = 8, 1.9 % at 16); its dual, the velocity
//!   condition, is eₖᵀv ≥ 0 for every k. With an edge along the slip (θ₀ from the slip's
//!   direction) a sliding contact gets Coulomb's force exactly.

use crate::rows::RowKind;

/// One friction contact of a row set: its normal row, the first of its one or two friction
/// rows (which follow the normal row), and μ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FrictionContact {
    /// Index of the normal row.
    pub(crate) normal: usize,
    /// How many friction rows (1 or 2) follow it.
    pub(crate) count: usize,
    /// μ.
    pub(crate) coefficient: f64,
}

impl FrictionContact {
    /// The indices of the contact's friction rows.
    pub(crate) fn tangents(&self) -> std::ops::Range<usize> {
        self.normal + 1..self.normal + 1 + self.count
    }

    /// The indices of the contact's rows, normal first.
    pub(crate) fn rows(&self) -> std::ops::Range<usize> {
        self.normal..self.normal + 1 + self.count
    }
}

/// The friction contacts of `kinds` (as `Problem` checked: a normal row, then its one or two
/// friction rows), in row order.
pub(crate) fn friction_contacts(kinds: &[RowKind]) -> impl Iterator<Item = FrictionContact> + '_ {
    let mut row = 0;
    std::iter::from_fn(move || {
        while row < kinds.len() {
            let RowKind::Friction { normal, coefficient } = kinds[row] else {
                row += 1;
                continue;
            };
            let second = matches!(kinds.get(row + 1), Some(RowKind::Friction { normal: n, .. }) if *n == normal);
            let count = 1 + usize::from(second);
            row += count;
            return Some(FrictionContact { normal, count, coefficient });
        }
        None
    })
}

/// The inscribed pyramid of a contact's friction cone (module docs): its edge rows and how
/// their multipliers βₖ make the contact's impulse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionPyramid {
    /// μ.
    pub coefficient: f64,
    /// Number of edges E (≥ 3).
    pub edges: usize,
    /// Angle θ₀ of the first edge from t₁ toward t₂ (rad).
    pub first_angle: f64,
}

impl FrictionPyramid {
    /// The direction dₖ = (cos θₖ, sin θₖ) of edge `k` in the tangent plane (t₁, t₂).
    pub fn direction(&self, k: usize) -> (f64, f64) {
        let theta = self.first_angle + std::f64::consts::TAU * k as f64 / self.edges as f64;
        (theta.cos(), theta.sin())
    }

    /// Writes edge `k`'s row eₖ = c_n + μ(cos θₖ c_t1 + sin θₖ c_t2) into `out`, and returns its
    /// right-hand side b_n + μ(cos θₖ b_t1 + sin θₖ b_t2), from the contact's normal row
    /// (`normal`, `b_n`) and tangent rows (`tangents`, `b_t`).
    pub fn edge_row(
        &self,
        k: usize,
        (normal, b_n): (&[f64], f64),
        (tangents, b_t): ([&[f64]; 2], [f64; 2]),
        out: &mut [f64],
    ) -> f64 {
        let (c, s) = self.direction(k);
        let mu = self.coefficient;
        for (((o, n), t1), t2) in out.iter_mut().zip(normal).zip(tangents[0]).zip(tangents[1]) {
            *o = n + mu * (c * t1 + s * t2);
        }
        b_n + mu * (c * b_t[0] + s * b_t[1])
    }

    /// The contact's impulse (λ_n, λ_t1, λ_t2) from its edges' multipliers `beta`.
    pub fn impulse(&self, beta: &[f64]) -> (f64, [f64; 2]) {
        let mut normal = 0.0;
        let mut tangent = [0.0, 0.0];
        for (k, &b) in beta.iter().enumerate() {
            let (c, s) = self.direction(k);
            normal += b;
            tangent[0] += self.coefficient * b * c;
            tangent[1] += self.coefficient * b * s;
        }
        (normal, tangent)
    }

    /// The smallest friction limit over directions, as a fraction of μλ_n: cos(π/E).
    pub fn worst_fraction(&self) -> f64 {
        (std::f64::consts::PI / self.edges as f64).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_normal_row_and_the_friction_rows_after_it_are_one_contact() {
        let f = |normal| RowKind::Friction { normal, coefficient: 0.5 };
        let kinds = [RowKind::Equality, RowKind::Inequality, f(1), f(1), RowKind::Inequality, f(4)];
        let contacts: Vec<_> = friction_contacts(&kinds).map(|c| (c.normal, c.count)).collect();
        assert_eq!(contacts, vec![(1, 2), (4, 1)]);
    }

    #[test]
    fn the_pyramid_lies_inside_the_cone_and_reaches_it_on_its_edges() {
        let pyramid = FrictionPyramid { coefficient: 0.3, edges: 8, first_angle: 0.2 };
        // One edge alone: on the cone's surface, λ_t = μλ_n dₖ.
        let (n, t) = pyramid.impulse(&[0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(n, 2.0);
        assert!((t[0].hypot(t[1]) - 0.6).abs() < 1e-15);
        // Two neighbouring edges equally: the polygon's side, cos(π/E) of the cone.
        let (n, t) = pyramid.impulse(&[1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!((t[0].hypot(t[1]) / (0.3 * n) - pyramid.worst_fraction()).abs() < 1e-15);
        // Any βₖ ≥ 0: inside the cone.
        let (n, t) = pyramid.impulse(&[0.3, 1.0, 0.0, 2.0, 0.1, 0.0, 0.7, 0.2]);
        assert!(t[0].hypot(t[1]) <= 0.3 * n);
        // The edge row is the normal row tilted by μ dₖ along the tangents.
        let mut row = [0.0; 2];
        let b = pyramid.edge_row(
            2,
            (&[1.0, 0.0], 0.5),
            ([&[0.0, 1.0], &[2.0, 0.0]], [0.0, 1.0]),
            &mut row,
        );
        let (c, s) = pyramid.direction(2);
        assert!((row[0] - (1.0 + 0.3 * 2.0 * s)).abs() < 1e-15 && (row[1] - 0.3 * c).abs() < 1e-15);
        assert!((b - (0.5 + 0.3 * s)).abs() < 1e-15);
    }
}
