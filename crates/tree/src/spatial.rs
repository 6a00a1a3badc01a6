//! Spatial algebra in world coordinates.
//!
//! Conventions (see `docs/physics.md`, "Kinematics and dynamics"): a spatial motion vector is `(ω; v)`, angular part
//! first. In this crate motion vectors are expressed in **world coordinates at the world
//! origin** ("Plücker at O"): `v` is the velocity of the body-fixed point that currently
//! coincides with the world origin, so the velocity of any point `x` is `v + ω × x`. Force
//! vectors (wrenches) are `(n; f)` with the moment `n` taken about the world origin.
//! Working at one point removes all frame-to-frame transforms from the recursions.

use std::ops::Range;

use glam::{DMat3, DVec3};

/// A rigid transform `E = (R, p)`: maps a point `x` in the child frame to `R x + p`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Rotation `R` (orthonormal, det +1).
    pub rotation: DMat3,
    /// Translation `p` (cm).
    pub translation: DVec3,
}

impl Transform {
    /// The identity transform.
    pub const IDENTITY: Self = Self { rotation: DMat3::IDENTITY, translation: DVec3::ZERO };

    /// A pure translation by `p` (cm).
    pub fn from_translation(p: DVec3) -> Self {
        Self { rotation: DMat3::IDENTITY, translation: p }
    }

    /// A pure rotation by `angle` (rad) about the unit `axis`.
    pub fn from_axis_angle(axis: DVec3, angle: f64) -> Self {
        Self { rotation: DMat3::from_axis_angle(axis, angle), translation: DVec3::ZERO }
    }

    /// Composition `self · other` (apply `other` first). When `other` is a pure translation
    /// (the joint and body offsets of a chain) `R · 1 = R` is not multiplied out: the same
    /// numbers, since the skipped terms are products with 0 and 1.
    pub fn mul(&self, other: &Transform) -> Transform {
        let rotation = if other.rotation == DMat3::IDENTITY {
            self.rotation
        } else {
            self.rotation * other.rotation
        };
        Transform { rotation, translation: self.rotation * other.translation + self.translation }
    }

    /// `self · Rot(axis, angle)`: this frame turned by `angle` (rad) about the unit `axis` of
    /// its own coordinates, as `self.mul(&Transform::from_axis_angle(axis, angle))`. About a
    /// coordinate axis (every joint of the hagfish) only the two columns that turn are
    /// multiplied out, from the entries `DMat3::from_axis_angle` gives them (cos θ, ±sin θ, and
    /// (1 − cos θ) + cos θ on the diagonal): the same numbers, since the skipped terms are
    /// products with 0.
    pub fn rotated(&self, axis: DVec3, angle: f64) -> Transform {
        let [x, y, z] = [self.rotation.x_axis, self.rotation.y_axis, self.rotation.z_axis];
        let (sin, cos) = angle.sin_cos();
        let diagonal = (1.0 - cos) + cos;
        let columns = if axis == DVec3::X {
            [x * diagonal, y * cos + z * sin, y * (0.0 - sin) + z * cos]
        } else if axis == DVec3::Y {
            [x * cos + z * (0.0 - sin), y * diagonal, x * sin + z * cos]
        } else if axis == DVec3::Z {
            [x * cos + y * sin, x * (0.0 - sin) + y * cos, z * diagonal]
        } else {
            return self.mul(&Transform::from_axis_angle(axis, angle));
        };
        Transform { rotation: DMat3::from_cols(columns[0], columns[1], columns[2]), ..*self }
    }

    /// The inverse `E⁻¹ = (Rᵀ, −Rᵀ p)`.
    pub fn inverse(&self) -> Transform {
        let rt = self.rotation.transpose();
        Transform { rotation: rt, translation: -(rt * self.translation) }
    }

    /// Maps a point from this frame to the parent frame: `R x + p`.
    pub fn transform_point(&self, x: DVec3) -> DVec3 {
        self.rotation * x + self.translation
    }
}

/// Spatial vectors stored one array per component (ω_x, ω_y, ω_z, v_x, v_y, v_z), so that a
/// loop over many of them against one fixed vector reads contiguous memory (and vectorises):
/// the CRBA's `M_ab = s_a · (I^c s_b)` and the point rows' `nᵀP` over the joint axes `s_a`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SpatialComponents {
    components: [Vec<f64>; 6],
}

impl SpatialComponents {
    /// Room for `count` vectors.
    pub fn with_capacity(count: usize) -> Self {
        Self { components: std::array::from_fn(|_| Vec::with_capacity(count)) }
    }

    /// Replaces the contents with `vectors`.
    pub fn fill_from(&mut self, vectors: &[Spatial]) {
        for (c, component) in self.components.iter_mut().enumerate() {
            component.clear();
            component.extend(vectors.iter().map(|s| match c {
                0..3 => s.angular[c],
                _ => s.linear[c - 3],
            }));
        }
    }

    /// [`Spatial::dot`] of each stored vector with index in `range` and `w`, in order and
    /// with the same operations (so the same values).
    ///
    /// # Panics
    /// If `range` reaches past the stored vectors.
    pub fn dots(&self, range: Range<usize>, w: &Spatial) -> impl Iterator<Item = f64> + '_ {
        let components = self.components.each_ref().map(|c| &c[range.clone()]);
        let w = *w;
        (0..range.len()).map(move |i| dot_at(&components, i, &w))
    }

    /// `outs[j][a] += s_a · w[j]` for each stored vector `s_a` with index `a` in `range` and
    /// each of the K vectors `w[j]`: [`dots`](Self::dots) of K vectors in one pass over the
    /// components (each read once for all K), with the same operations (so the same values).
    ///
    /// # Panics
    /// If `range` reaches past the stored vectors or past an output.
    pub fn add_dots<const K: usize>(
        &self,
        range: Range<usize>,
        w: &[Spatial; K],
        outs: &mut [&mut [f64]; K],
    ) {
        let components = self.components.each_ref().map(|c| &c[range.clone()]);
        let mut outs = outs.each_mut().map(|out| &mut out[range.clone()]);
        for i in 0..range.len() {
            for (out, w) in outs.iter_mut().zip(w) {
                out[i] += dot_at(&components, i, w);
            }
        }
    }
}

/// [`Spatial::dot`] of the vector `i` of `components` (ω_x, ω_y, ω_z, v_x, v_y, v_z) with `w`,
/// summed as `Spatial::dot` sums.
#[inline(always)]
fn dot_at(components: &[&[f64]; 6], i: usize, w: &Spatial) -> f64 {
    let [wx, wy, wz, vx, vy, vz] = components;
    let (a, l) = (w.angular, w.linear);
    (wx[i] * a.x + wy[i] * a.y + wz[i] * a.z) + (vx[i] * l.x + vy[i] * l.y + vz[i] * l.z)
}

/// A spatial motion vector `(ω; v)` (twist) or force vector `(n; f)` (wrench); which one is
/// meant is stated by the field or function that holds it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Spatial {
    /// Angular part: `ω` (rad/s) for motion, the moment `n` (dyn·cm) for force.
    pub angular: DVec3,
    /// Linear part: `v` (cm/s) for motion, the force `f` (dyn) for force.
    pub linear: DVec3,
}

impl Spatial {
    /// The zero vector.
    pub const ZERO: Self = Self { angular: DVec3::ZERO, linear: DVec3::ZERO };

    /// Builds from the angular and linear parts.
    pub const fn new(angular: DVec3, linear: DVec3) -> Self {
        Self { angular, linear }
    }

    /// The unit twist of a rotation about the line through `point` along the unit `axis`:
    /// `(a; point × a)`.
    pub fn revolute_axis(axis: DVec3, point: DVec3) -> Self {
        Self { angular: axis, linear: point.cross(axis) }
    }

    /// The unit twist of a translation along the unit `direction`: `(0; direction)`.
    pub fn prismatic_axis(direction: DVec3) -> Self {
        Self { angular: DVec3::ZERO, linear: direction }
    }

    /// The wrench at the world origin of a force `f` applied at the point `x`: `(x × f; f)`.
    pub fn point_force(x: DVec3, f: DVec3) -> Self {
        Self { angular: x.cross(f), linear: f }
    }

    /// The pairing of a motion and a force vector: power `ω·n + v·f`.
    pub fn dot(&self, other: &Spatial) -> f64 {
        self.angular.dot(other.angular) + self.linear.dot(other.linear)
    }

    /// `self × m` for motion vectors (`crm`): `(ω × ω_m; ω × v_m + v × ω_m)`. The time
    /// derivative of a motion vector fixed in a frame moving with twist `self`.
    pub fn cross_motion(&self, m: &Spatial) -> Spatial {
        Spatial {
            angular: self.angular.cross(m.angular),
            linear: self.angular.cross(m.linear) + self.linear.cross(m.angular),
        }
    }

    /// `self ×* f` for a force vector (`crf`): `(ω × n + v × f; ω × f)`.
    pub fn cross_force(&self, f: &Spatial) -> Spatial {
        Spatial {
            angular: self.angular.cross(f.angular) + self.linear.cross(f.linear),
            linear: self.angular.cross(f.linear),
        }
    }

    /// Expresses a world twist at the origin in the body frame `E = (R, p)`:
    /// `Ad(E⁻¹)·(ω; v) = (Rᵀω; Rᵀ(v + ω × p))`.
    pub fn to_body(&self, frame: &Transform) -> Spatial {
        let rt = frame.rotation.transpose();
        Spatial {
            angular: rt * self.angular,
            linear: rt * (self.linear + self.angular.cross(frame.translation)),
        }
    }

    /// The velocity of the point `x` (world coordinates) moving with this twist: `v + ω × x`.
    pub fn point_velocity(&self, x: DVec3) -> DVec3 {
        self.linear + self.angular.cross(x)
    }

    /// Component-wise `self + s·other`.
    pub fn add_scaled(&self, other: &Spatial, s: f64) -> Spatial {
        Spatial {
            angular: self.angular + other.angular * s,
            linear: self.linear + other.linear * s,
        }
    }
}

impl std::ops::Add for Spatial {
    type Output = Spatial;
    fn add(self, o: Spatial) -> Spatial {
        Spatial { angular: self.angular + o.angular, linear: self.linear + o.linear }
    }
}

impl std::ops::AddAssign for Spatial {
    fn add_assign(&mut self, o: Spatial) {
        self.angular += o.angular;
        self.linear += o.linear;
    }
}

impl std::ops::Sub for Spatial {
    type Output = Spatial;
    fn sub(self, o: Spatial) -> Spatial {
        Spatial { angular: self.angular - o.angular, linear: self.linear - o.linear }
    }
}

impl std::ops::Mul<f64> for Spatial {
    type Output = Spatial;
    fn mul(self, s: f64) -> Spatial {
        Spatial { angular: self.angular * s, linear: self.linear * s }
    }
}

/// The spatial inertia of a rigid body (or a rigid composite) at the world origin, in the
/// compact form `(m, h = m c, I_O)` with `c` the centre of mass and `I_O` the rotational
/// inertia about the origin. As a 6×6 matrix it is `[[I_O, [h]], [[h]ᵀ, m·1]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidInertia {
    /// Mass `m` (g).
    pub mass: f64,
    /// First moment `h = m c` (g·cm).
    pub first_moment: DVec3,
    /// Rotational inertia about the world origin `I_O = R I_c Rᵀ + m([c]ᵀ[c])` (g·cm²).
    pub rotational: DMat3,
}

impl RigidInertia {
    /// The zero inertia.
    pub const ZERO: Self = Self { mass: 0.0, first_moment: DVec3::ZERO, rotational: DMat3::ZERO };

    /// The world inertia of a body of mass `m` with principal moments `principal` (about its
    /// body axes through the centre of mass) whose body frame is `frame` (origin at the
    /// centre of mass): `I_O = R diag(I) Rᵀ + m(|c|²·1 − c cᵀ)`.
    pub fn from_body(mass: f64, principal: DVec3, frame: &Transform) -> Self {
        let r = frame.rotation;
        let c = frame.translation;
        let rotated = r * DMat3::from_diagonal(principal) * r.transpose();
        let parallel = DMat3::from_diagonal(DVec3::splat(c.length_squared())) - outer(c, c);
        Self { mass, first_moment: c * mass, rotational: rotated + parallel * mass }
    }

    /// A point mass `m` at the world point `x`: `(m, m x, m(|x|²·1 − x xᵀ))`. Also the form of
    /// a point damper of coefficient `m` (dyn·s/cm) at `x`.
    pub fn point(mass: f64, x: DVec3) -> Self {
        let parallel = DMat3::from_diagonal(DVec3::splat(x.length_squared())) - outer(x, x);
        Self { mass, first_moment: x * mass, rotational: parallel * mass }
    }

    /// Adds `s · other` in place.
    pub fn add_scaled(&mut self, other: &RigidInertia, s: f64) {
        self.mass += s * other.mass;
        self.first_moment += other.first_moment * s;
        self.rotational += other.rotational * s;
    }

    /// The momentum of a twist: `I·(ω; v) = (I_O ω + h × v; m v − h × ω)`.
    pub fn apply(&self, twist: &Spatial) -> Spatial {
        Spatial {
            angular: self.rotational * twist.angular + self.first_moment.cross(twist.linear),
            linear: twist.linear * self.mass - self.first_moment.cross(twist.angular),
        }
    }
}

impl std::ops::AddAssign for RigidInertia {
    fn add_assign(&mut self, o: RigidInertia) {
        self.mass += o.mass;
        self.first_moment += o.first_moment;
        self.rotational += o.rotational;
    }
}

/// The outer product `a bᵀ`.
pub fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> Transform {
        Transform {
            rotation: DMat3::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 0.7),
            translation: DVec3::new(0.3, -1.2, 2.0),
        }
    }

    #[test]
    fn component_dots_equal_spatial_dots_bit_for_bit() {
        let vectors: Vec<Spatial> = (0..7)
            .map(|i| {
                let t = f64::from(i);
                Spatial::new(
                    DVec3::new(t.sin(), 0.3 * t, -1.7 + t * t),
                    DVec3::new(1.0 / (1.0 + t), t.cos(), 2.5),
                )
            })
            .collect();
        let w = Spatial::new(DVec3::new(0.7, -1.3, 0.11), DVec3::new(3.0, 0.2, -0.9));
        let mut components = SpatialComponents::with_capacity(vectors.len());
        components.fill_from(&vectors);
        let dots: Vec<f64> = components.dots(2..6, &w).collect();
        let expected: Vec<f64> = vectors[2..6].iter().map(|v| v.dot(&w)).collect();
        assert_eq!(dots, expected);
    }

    /// The general product `R · Rot(a, θ)` (glam's 3×3 product, every term multiplied out).
    fn multiplied_out(e: &Transform, axis: DVec3, angle: f64) -> Transform {
        let r = DMat3::from_axis_angle(axis, angle);
        Transform {
            rotation: e.rotation * r,
            translation: e.rotation * DVec3::ZERO + e.translation,
        }
    }

    /// The shortcuts of `rotated` and of `mul` by a pure translation give the numbers of the
    /// products multiplied out, bit for bit (so runs do not change by taking them).
    #[test]
    fn rotations_about_coordinate_axes_and_translations_match_the_full_products_bit_for_bit() {
        let e = frame();
        let oblique = DVec3::new(0.3, -0.4, 0.5).normalize();
        for axis in [DVec3::X, DVec3::Y, DVec3::Z, oblique] {
            for angle in [0.0, 1e-9, -0.37, 0.8, 2.9, -3.1] {
                let (short, full) = (e.rotated(axis, angle), multiplied_out(&e, axis, angle));
                assert_eq!(
                    short.rotation.to_cols_array(),
                    full.rotation.to_cols_array(),
                    "{axis} {angle}"
                );
                assert_eq!(short.translation, full.translation, "{axis} {angle}");
            }
        }
        let offset = Transform::from_translation(DVec3::new(0.424, 0.0, 0.0));
        let full = Transform {
            rotation: e.rotation * DMat3::IDENTITY,
            translation: e.rotation * offset.translation + e.translation,
        };
        assert_eq!(e.mul(&offset), full);
    }

    #[test]
    fn inverse_composes_to_identity() {
        let e = frame();
        let id = e.mul(&e.inverse());
        assert!((id.rotation - DMat3::IDENTITY).abs().to_cols_array().iter().all(|v| *v < 1e-14));
        assert!(id.translation.length() < 1e-14);
    }

    #[test]
    fn inertia_momentum_matches_point_mass_sum() {
        // A body's momentum equals Σ m v over a point-mass model with the same inertia:
        // use a single point mass (zero principal moments).
        let e = frame();
        let m = 2.5;
        let inertia = RigidInertia::from_body(m, DVec3::ZERO, &e);
        let twist = Spatial::new(DVec3::new(0.2, -0.4, 1.1), DVec3::new(-3.0, 0.5, 0.25));
        let v = twist.point_velocity(e.translation);
        let momentum = inertia.apply(&twist);
        assert!((momentum.linear - v * m).length() < 1e-12);
        assert!((momentum.angular - e.translation.cross(v * m)).length() < 1e-12);
    }

    #[test]
    fn to_body_gives_body_origin_velocity() {
        let e = frame();
        let twist = Spatial::new(DVec3::new(0.2, -0.4, 1.1), DVec3::new(-3.0, 0.5, 0.25));
        let body = twist.to_body(&e);
        let world_origin_velocity = twist.point_velocity(e.translation);
        assert!((e.rotation * body.linear - world_origin_velocity).length() < 1e-12);
        assert!((e.rotation * body.angular - twist.angular).length() < 1e-12);
    }
}
