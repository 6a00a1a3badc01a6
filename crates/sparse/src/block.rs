//! Dense 6 × 6 blocks of the maximal-coordinate system (spatial inertias, articulated
//! inertias), in the `(angular; linear)` order of [`Spatial`].

use hagfish_tree::{RigidInertia, Spatial};

use crate::factor::MAX_JOINT_DOFS;

/// A 6 × 6 matrix acting on spatial vectors, row-major, `(angular; linear)` order. Used for
/// symmetric blocks (inertias and articulated inertias).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Block6(pub(crate) [[f64; 6]; 6]);

impl Block6 {
    /// The zero block.
    pub(crate) const ZERO: Self = Self([[0.0; 6]; 6]);

    /// The 6 × 6 matrix of a rigid inertia at the origin: `[[I_O, [h]], [[h]ᵀ, m·1]]`, so that
    /// `Block6::from(I)·v = I.apply(v)`.
    pub(crate) fn from_inertia(inertia: &RigidInertia) -> Self {
        let mut b = Self::ZERO;
        let rot = inertia.rotational.to_cols_array_2d();
        let h = inertia.first_moment;
        let skew = [[0.0, -h.z, h.y], [h.z, 0.0, -h.x], [-h.y, h.x, 0.0]];
        for i in 0..3 {
            for j in 0..3 {
                b.0[i][j] = rot[j][i];
                b.0[i][j + 3] = skew[i][j];
                b.0[i + 3][j] = skew[j][i];
            }
            b.0[i + 3][i + 3] = inertia.mass;
        }
        b
    }

    /// `B·v`.
    pub(crate) fn apply(&self, v: &Spatial) -> Spatial {
        let x = to_array(v);
        let mut y = [0.0; 6];
        for (yi, row) in y.iter_mut().zip(&self.0) {
            *yi = row.iter().zip(&x).map(|(a, b)| a * b).sum();
        }
        from_array(&y)
    }

    /// `B ← B + (A − Σ_k u_k u_kᵀ)`, the downdates subtracted from each entry of A in the
    /// order of `downdates` (at most [`MAX_JOINT_DOFS`]) before it is added: a child's
    /// articulated inertia less its joint's gains, added to its parent's, without forming the
    /// child's block.
    pub(crate) fn add_downdated(&mut self, other: &Block6, downdates: &[Spatial]) {
        let mut u = [[0.0; 6]; MAX_JOINT_DOFS];
        for (array, spatial) in u.iter_mut().zip(downdates) {
            *array = to_array(spatial);
        }
        let u = &u[..downdates.len()];
        for (i, (row, other_row)) in self.0.iter_mut().zip(&other.0).enumerate() {
            for (j, (a, b)) in row.iter_mut().zip(other_row).enumerate() {
                let mut child = *b;
                for uk in u {
                    child -= uk[i] * uk[j];
                }
                *a += child;
            }
        }
    }
}

/// `(ω; v)` as `[ω_x, ω_y, ω_z, v_x, v_y, v_z]`.
pub(crate) fn to_array(v: &Spatial) -> [f64; 6] {
    [v.angular.x, v.angular.y, v.angular.z, v.linear.x, v.linear.y, v.linear.z]
}

/// The inverse of [`to_array`].
pub(crate) fn from_array(a: &[f64; 6]) -> Spatial {
    Spatial::new(glam::DVec3::new(a[0], a[1], a[2]), glam::DVec3::new(a[3], a[4], a[5]))
}

#[cfg(test)]
mod tests {
    use glam::{DMat3, DVec3};
    use hagfish_tree::Transform;

    use super::*;

    #[test]
    fn block_of_an_inertia_applies_like_the_inertia() {
        let frame = Transform {
            rotation: DMat3::from_axis_angle(DVec3::new(1.0, -2.0, 0.5).normalize(), 0.9),
            translation: DVec3::new(1.5, -0.3, 2.2),
        };
        let inertia = RigidInertia::from_body(1.7, DVec3::new(0.2, 0.5, 0.6), &frame);
        let twist = Spatial::new(DVec3::new(0.3, -1.1, 0.4), DVec3::new(2.0, 0.7, -0.9));
        let expected = inertia.apply(&twist);
        let got = Block6::from_inertia(&inertia).apply(&twist);
        assert!((got - expected).angular.length() < 1e-12);
        assert!((got - expected).linear.length() < 1e-12);
    }

    #[test]
    fn downdated_block_is_added_entry_by_entry() {
        let entry = |i: usize, j: usize, scale: f64| scale * ((i * 6 + j) as f64 * 0.37).sin();
        let (mut b, mut a) = (Block6::ZERO, Block6::ZERO);
        for i in 0..6 {
            for j in 0..6 {
                b.0[i][j] = entry(i, j, 2.0);
                a.0[i][j] = entry(j, i, 3.0);
            }
        }
        let u = [
            Spatial::new(DVec3::new(1.0, 2.0, 3.0), DVec3::new(-1.0, 0.5, 0.0)),
            Spatial::new(DVec3::new(0.3, -0.7, 0.1), DVec3::new(0.9, 0.2, -0.4)),
        ];
        let before = b;
        b.add_downdated(&a, &u);
        let (u0, u1) = (to_array(&u[0]), to_array(&u[1]));
        for i in 0..6 {
            for j in 0..6 {
                let child = a.0[i][j] - u0[i] * u0[j] - u1[i] * u1[j];
                assert_eq!(b.0[i][j], before.0[i][j] + child, "entry ({i}, {j})");
            }
        }
        // The downdate alone: (0 − u uᵀ) v = −u (uᵀv), uᵀv = 1 + 0.5.
        let mut downdate = Block6::ZERO;
        downdate.add_downdated(&Block6::ZERO, &u[..1]);
        let got = downdate.apply(&Spatial::new(DVec3::X, DVec3::Y));
        assert!((got - u[0] * -1.5).angular.length() < 1e-14);
        assert!((got - u[0] * -1.5).linear.length() < 1e-14);
    }
}
