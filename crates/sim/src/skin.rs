//! The skin: a compressible outer layer of the contact tube over a hard core
//! (`docs/physics.md`, "Skin").
//!
//! A body with a [`hagfish_tree::Skin`] of thickness t and pressure p has a core of radius
//! r − t. A self contact with tube gap g (between the outer surfaces) compresses the two skins
//! by δ = −g in all, and their core gap is g_c = g + t_a + t_b (t at each contact point, blended
//! along the spline like the radius). Two rows hold it:
//!
//! - the core row, the hard non-penetration row of a rigid tube on the core gap g_c;
//! - the skin row, a compliant row (an implicit spring; `hagfish_solver::RowKind::Compliant`)
//!   on the outer gap, `ḋ + ελ ≥ −g/h` with ε = 1/(k h²) and the stiffness of a pressurised
//!   membrane pressed by a crossing tube, k = π p √(r_a r_b) (force p on the contact patch,
//!   whose area π√(r_a r_b)·δ grows linearly with the compression).
//!
//! A body without a skin has t = 0: its contacts get the core row alone, on g_c = g, exactly
//! as a rigid tube's.
//!
//! The springs are one per record at the body-relative cluster radius, which keeps one record
//! every 0.1875 × `contact_exclusion_diameters` local diameters (0.375 D by default) along a
//! line contact on every
//! chain. A step retried with contacts at the chain's finer resolution has several records on
//! each such stretch: all get core rows, but only those the body-relative radius keeps
//! ([`SkinRecords`]) get springs, so the skin pushes as hard as in the step it replaces.

use hagfish_geometry::{Centreline, CoarserClusters, SelfContact, SplineWeights};
use hagfish_tree::Model;

/// The skins of a model's bodies, per body (thickness 0 and pressure 0 where there is none).
#[derive(Debug, Clone, Default)]
pub struct SkinLayer {
    thickness: Vec<f64>,
    pressure: Vec<f64>,
    present: bool,
}

/// What the skin does at one self contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSkin {
    /// t_a + t_b (cm): how far the two skins can be compressed together.
    pub thickness: f64,
    /// The gap between the cores, g + t_a + t_b (cm).
    pub core_gap: f64,
    /// The spring stiffness k = π p √(r_a r_b) (dyn/cm), p the mean pressure of the skinned
    /// sides.
    pub stiffness: f64,
}

impl SkinLayer {
    /// The skins of `model`'s bodies.
    pub fn new(model: &Model) -> Self {
        let skins = model.bodies().iter().map(|body| body.skin);
        let thickness = skins.clone().map(|s| s.map_or(0.0, |s| s.thickness)).collect();
        let pressure = skins.clone().map(|s| s.map_or(0.0, |s| s.pressure)).collect();
        Self { thickness, pressure, present: model.bodies().iter().any(|b| b.skin.is_some()) }
    }

    /// True when some body has a skin.
    pub fn is_present(&self) -> bool {
        self.present
    }

    /// The core radii r − t of the bodies with radii `radii`.
    pub fn core_radii(&self, radii: &[f64]) -> Vec<f64> {
        radii.iter().zip(&self.thickness).map(|(r, t)| r - t).collect()
    }

    /// The gap between the cores at `contact`, g + t_a + t_b (cm), or g itself, unchanged,
    /// where neither point has a skin.
    pub fn core_gap(&self, contact: &SelfContact) -> f64 {
        if !self.present {
            return contact.gap;
        }
        let thickness =
            blend(&self.thickness, &contact.weights_a) + blend(&self.thickness, &contact.weights_b);
        if thickness > 0.0 { contact.gap + thickness } else { contact.gap }
    }

    /// The skin at `contact` on `centreline`, or `None` where neither point has one (the
    /// contact is then a rigid tube's, its gap the core gap exactly).
    pub fn at(&self, contact: &SelfContact, centreline: &Centreline) -> Option<ContactSkin> {
        if !self.present {
            return None;
        }
        let (t_a, t_b) = (
            blend(&self.thickness, &contact.weights_a),
            blend(&self.thickness, &contact.weights_b),
        );
        let thickness = t_a + t_b;
        if thickness <= 0.0 {
            return None;
        }
        let pressures = [
            (t_a, blend(&self.pressure, &contact.weights_a)),
            (t_b, blend(&self.pressure, &contact.weights_b)),
        ];
        let skinned = pressures.iter().filter(|(t, _)| *t > 0.0);
        let (sum, count) = skinned.fold((0.0, 0.0), |(sum, n), (_, p)| (sum + p, n + 1.0));
        let (r_a, r_b) = (centreline.radius(contact.u_a), centreline.radius(contact.u_b));
        Some(ContactSkin {
            thickness,
            core_gap: contact.gap + thickness,
            stiffness: std::f64::consts::PI * (sum / count) * (r_a * r_b).sqrt(),
        })
    }
}

/// Which self contacts carry a skin spring ([module docs](self)): every one detected at the
/// body-relative cluster radius, and of those detected at a finer radius the ones that radius
/// keeps (deepest first, [`CoarserClusters`]).
#[derive(Debug, Clone, Default)]
pub struct SkinRecords {
    body_relative_radius: f64,
    coarser: CoarserClusters,
}

impl SkinRecords {
    /// For contacts whose body-relative cluster radius is `body_relative_radius` (bodies),
    /// with room for `records` contacts.
    pub fn new(body_relative_radius: f64, records: usize) -> Self {
        let mut coarser = CoarserClusters::default();
        coarser.reserve(records);
        Self { body_relative_radius, coarser }
    }

    /// One flag per record of `contacts`, detected at cluster radius `detected_radius`:
    /// whether it carries a spring; `None` when every record does (detected at the
    /// body-relative radius or a coarser one).
    pub fn carriers(&mut self, contacts: &[SelfContact], detected_radius: f64) -> Option<&[bool]> {
        (detected_radius < self.body_relative_radius)
            .then(|| self.coarser.keep(contacts, self.body_relative_radius))
    }
}

/// Σ w_m v_m over the bodies and weights of a spline point: a per-body value at that point.
fn blend(values: &[f64], weights: &SplineWeights) -> f64 {
    weights.iter().map(|(body, w)| w * values[body]).sum()
}

impl ContactSkin {
    /// The compliance ε = 1/(k h²) (1/g) of the skin row at time step `h`.
    pub fn compliance(&self, time_step: f64) -> f64 {
        1.0 / (self.stiffness * time_step * time_step)
    }

    /// The compression of the skins at outer gap `gap`, as a fraction of t_a + t_b (0 when
    /// open, 1 when the cores touch).
    pub fn compression(&self, gap: f64) -> f64 {
        ((-gap).max(0.0) / self.thickness).min(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compliance_is_one_over_k_h_squared_and_compression_a_fraction_of_the_skins() {
        let skin = ContactSkin { thickness: 0.4, core_gap: 0.3, stiffness: 1000.0 };
        assert_eq!(skin.compliance(0.01), 1.0 / (1000.0 * 1e-4));
        assert_eq!(skin.compression(0.1), 0.0);
        assert_eq!(skin.compression(-0.1), 0.25);
        assert_eq!(skin.compression(-1.0), 1.0);
    }
}
