//! Joint types: each joint is a sequence of at most three one-DOF motions (rotations about, or
//! translations along, axes of its own frame).
//!
//! A revolute joint about `a` is `Q(q) = Rot(a, q)`. The hagfish's universal joint is
//! `Q(q) = Ry(q₁)·Rz(q₂)` (yaw then pitch about the moving axis): in the child frame its motion
//! subspace is `S = [(sin q₂, cos q₂, 0), (0, 0, 1)]` (angular columns), which never loses rank,
//! so the joint has no gimbal singularity. Treating a universal joint as two successive
//! revolutes makes every recursion in this crate one code path.
//!
//! A translation joint moves its frame by `q₁e_x + q₂e_y + q₃e_z` without turning it: its
//! motion subspace is `S = [(0; e_x), (0; e_y), (0; e_z)]` (linear columns), constant in the
//! joint frame. It frees a root from the world (a block on an incline, a rope's pulled end);
//! the recursions treat its DOFs like any other, through their spatial axes.

use glam::DVec3;

/// The kind of a joint, which fixes its degrees of freedom and their axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointKind {
    /// No degree of freedom: the body is welded to its parent.
    Fixed,
    /// One rotation about a unit axis of the joint frame (the hagfish's twist joint uses +X).
    Revolute {
        /// Unit rotation axis in the joint frame.
        axis: DVec3,
    },
    /// Two rotations, first about +Y then about the rotated +Z: `Ry(q₁)·Rz(q₂)` (the
    /// hagfish's bending joint, with the body along +X).
    UniversalYz,
    /// Three translations along the joint frame's X, Y and Z (cm), in that order.
    Translation,
}

impl JointKind {
    /// The number of degrees of freedom (0 to 3).
    pub fn dof_count(&self) -> usize {
        match self {
            JointKind::Fixed => 0,
            JointKind::Revolute { .. } => 1,
            JointKind::UniversalYz => 2,
            JointKind::Translation => 3,
        }
    }

    /// The axis of DOF `k`, expressed in the frame reached after the motions of DOFs `0..k`
    /// (so successive rotations compose as `Rot(a₀, q₀)·Rot(a₁, q₁)`): the rotation axis, or
    /// for a [`translates`](Self::translates) joint the direction of travel.
    pub fn axis(&self, k: usize) -> DVec3 {
        match (self, k) {
            (JointKind::Revolute { axis }, _) => *axis,
            (JointKind::UniversalYz, 0) | (JointKind::Translation, 1) => DVec3::Y,
            (JointKind::Translation, 0) => DVec3::X,
            _ => DVec3::Z,
        }
    }

    /// True when the joint's DOFs are translations (q in cm, generalized forces in dyn);
    /// otherwise they are rotations (rad, dyn·cm).
    pub fn translates(&self) -> bool {
        matches!(self, JointKind::Translation)
    }

    /// A short name for tables: "fixed", "revolute", "universal", "translation".
    pub fn name(&self) -> &'static str {
        match self {
            JointKind::Fixed => "fixed",
            JointKind::Revolute { .. } => "revolute",
            JointKind::UniversalYz => "universal",
            JointKind::Translation => "translation",
        }
    }
}

/// Parameters of one degree of freedom: spring, damper and limits. Angles and torques for a
/// rotation; for a translation read cm for rad and dyn for dyn·cm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DofParams {
    /// Spring stiffness `k` (dyn·cm/rad): torque `−k (q − q_rest)`.
    pub stiffness: f64,
    /// Damping `d` (dyn·cm·s/rad): torque `−d q̇`, integrated implicitly.
    pub damping: f64,
    /// Rest angle `q_rest` (rad).
    pub rest: f64,
    /// Lower limit (rad); `-inf` for none.
    pub lower: f64,
    /// Upper limit (rad); `+inf` for none.
    pub upper: f64,
}

impl Default for DofParams {
    fn default() -> Self {
        Self {
            stiffness: 0.0,
            damping: 0.0,
            rest: 0.0,
            lower: f64::NEG_INFINITY,
            upper: f64::INFINITY,
        }
    }
}
