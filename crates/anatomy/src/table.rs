//! The derived per-body table (D5–D8): where each body sits, its radius and mass, its joint
//! and the joint's limits. [`Biometrics::to_model`] builds the tree from it and the CLI
//! prints it.

use std::f64::consts::PI;

use glam::DVec3;
use hagfish_tree::JointKind;

use crate::biometrics::Biometrics;
use crate::error::AnatomyError;

/// The range of one degree of freedom (deg), `lower < upper`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LimitDeg {
    /// Lower limit (deg).
    pub lower: f64,
    /// Upper limit (deg).
    pub upper: f64,
}

impl LimitDeg {
    /// The symmetric range `±theta` (deg).
    pub fn symmetric(theta: f64) -> Self {
        Self { lower: -theta, upper: theta }
    }
}

/// One body of the chain and the joint at its proximal end.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyRow {
    /// Body (= joint) index, 0 at the head.
    pub index: usize,
    /// Arc-length fraction `s/L` of the body's centre, `(i + ½)/N`.
    pub centre_fraction: f64,
    /// Arc-length fraction of the joint (the body's proximal end), `i/N`.
    pub joint_fraction: f64,
    /// Radius `r_i = r(centre_fraction)` (cm).
    pub radius_cm: f64,
    /// Mass `m_i = ρ π r_i² ℓ` (g).
    pub mass_g: f64,
    /// The joint: even index → revolute about +X (twist), odd → universal `Ry·Rz` (bend), D8.
    pub joint: JointKind,
    /// Limits per DOF of the joint (deg): `±twist` for a revolute, `±θ(joint_fraction)` on
    /// both DOFs of a universal.
    pub limits_deg: Vec<LimitDeg>,
}

/// The derived chain: N equal-length cylinders whose masses sum to the specimen's mass.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyTable {
    /// Body length `ℓ = L/N` (cm).
    pub segment_length_cm: f64,
    /// Total volume `V = Σ π r_i² ℓ` (cm³).
    pub volume_cm3: f64,
    /// Density `ρ = M/V` (g/cm³), chosen so that the masses sum to M.
    pub density_g_per_cm3: f64,
    /// One row per body, head first.
    pub rows: Vec<BodyRow>,
}

impl BodyTable {
    /// Number of reduced coordinates (Σ DOFs over the joints).
    pub fn dof_count(&self) -> usize {
        self.rows.iter().map(|r| r.limits_deg.len()).sum()
    }

    /// Σ m_i (g).
    pub fn total_mass_g(&self) -> f64 {
        self.rows.iter().map(|r| r.mass_g).sum()
    }
}

/// The joint of body `index` (D8): revolute about +X for even indices (the root included),
/// universal `Ry(q₁)·Rz(q₂)` for odd ones.
pub fn joint_kind(index: usize) -> JointKind {
    if index.is_multiple_of(2) {
        JointKind::Revolute { axis: DVec3::X }
    } else {
        JointKind::UniversalYz
    }
}

impl Biometrics {
    /// Validates and derives the per-body table: `ℓ = L/N`; body `i` centred at
    /// `u = (i + ½)/N` with radius `r(u)` ([`Biometrics::radius_at`]); `ρ = M / Σ π r_i² ℓ`
    /// and `m_i = ρ π r_i² ℓ`, so Σ m_i = M; limits from [`joint_kind`], the twist limit and
    /// [`Biometrics::bending_limit_deg_at`] at the joint, `u = i/N`, scaled to this body count
    /// by [`Biometrics::joint_limit_deg`] (D16).
    pub fn body_table(&self) -> Result<BodyTable, AnatomyError> {
        self.validate()?;
        let n = self.body_count as f64;
        let ell = self.length_cm / n;
        let radii: Vec<f64> =
            (0..self.body_count).map(|i| self.radius_at((i as f64 + 0.5) / n)).collect();
        let volume: f64 = radii.iter().map(|r| PI * r * r * ell).sum();
        let density = self.mass_g / volume;
        if !(volume.is_finite() && volume > 0.0 && density.is_finite() && density > 0.0) {
            return Err(AnatomyError::DegenerateDensity { volume_cm3: volume, density });
        }
        let rows = radii
            .iter()
            .enumerate()
            .map(|(index, &r)| {
                let joint_fraction = index as f64 / n;
                let joint = joint_kind(index);
                let limit = self.joint_limit_deg(match joint {
                    JointKind::Revolute { .. } => self.twist_limit_deg,
                    _ => self.bending_limit_deg_at(joint_fraction),
                });
                BodyRow {
                    index,
                    centre_fraction: (index as f64 + 0.5) / n,
                    joint_fraction,
                    radius_cm: r,
                    mass_g: density * PI * r * r * ell,
                    joint,
                    limits_deg: vec![LimitDeg::symmetric(limit); joint.dof_count()],
                }
            })
            .collect();
        Ok(BodyTable {
            segment_length_cm: ell,
            volume_cm3: volume,
            density_g_per_cm3: density,
            rows,
        })
    }
}
