//! Where obstacles touch the tube: its axis sampled finely enough that no obstacle edge hides
//! between two samples deeper than a stated fraction of the local radius.
//!
//! The wall and, before this file, the obstacles saw each body as a sphere of radius r_k at its
//! centre. Two spheres a distance δ apart along the axis leave a groove between them: a sharp
//! edge can reach r − √(r² − δ²/4) into the tube there unseen (for a convex obstacle of
//! radius R less: (r + R) − √((r + R)² − δ²/4)). On ES103 at 100 bodies (δ ≈ 0.42 cm,
//! r ≈ 0.9 cm) that is 0.025 cm, below the contact margin; on Choi et al.'s rod at 600 bodies
//! (δ = 0.167 cm, r = 0.16 cm) 14 % of the radius, and a coarse body touches a thin pole as a
//! string of beads.
//!
//! So the segment between centres k and k + 1 is sampled at n_k points u = k + j/n_k,
//! j = 0 … n_k − 1 (the centre itself first), and the last centre closes the chain, with
//! n_k = ⌈δ_k / δ_max⌉, δ_k = (ℓ_k + ℓ_{k+1})/2 the centres' distance on a straight chain of
//! bodies ℓ long joined at their ends, and δ_max = 2 r √(f(2 − f)) the spacing at which the
//! groove is f r deep, r = min(r_k, r_{k+1}). Each sample is a sphere of the tube's radius
//! r(u) at the spline point x(u) = Σ w_m c_m: its contact's rows blend the bodies' velocities
//! with the weights w_m, as a self contact's do. Where n_k = 1 only the centres are samples,
//! each as before (a body's sphere, bit for bit).

use crate::error::GeometryError;

/// One point of the tube's axis that obstacles touch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TubeSample {
    /// Spline parameter u (a body index at a centre).
    pub u: f64,
    /// The body whose centre this is, `None` between centres.
    pub centre_of: Option<usize>,
}

/// The points of the tube's axis that obstacles touch (module docs), fixed for a body.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TubeSamples {
    samples: Vec<TubeSample>,
}

/// The default largest groove between two samples, as a fraction f of the local radius.
pub const DEFAULT_GROOVE_FRACTION: f64 = 0.05;

impl TubeSamples {
    /// Samples for a chain of bodies of lengths `lengths` (cm) and radii `radii` (cm), with
    /// grooves at most `groove_fraction` (f, in (0, 1]) of the local radius deep; with `None`
    /// the centres alone, a chain of beads (the wall's model of the body, and a chain whose
    /// links are straight between joints at their centres, like a rope over pegs).
    ///
    /// # Errors
    /// [`GeometryError::InvalidOption`] if f is not in (0, 1], the two lists differ in length,
    /// or a length or radius is not finite and > 0.
    pub fn new(
        lengths: &[f64],
        radii: &[f64],
        groove_fraction: Option<f64>,
    ) -> Result<TubeSamples, GeometryError> {
        let f = groove_fraction.unwrap_or(1.0);
        GeometryError::require_option(f > 0.0 && f <= 1.0, "groove fraction", "in (0, 1]", f)?;
        let count = lengths.len() as f64;
        GeometryError::require_option(
            radii.len() == lengths.len(),
            "tube sample radii",
            "one per body",
            count,
        )?;
        for &value in lengths.iter().chain(radii) {
            let valid = value.is_finite() && value > 0.0;
            GeometryError::require_option(valid, "body length or radius", "finite and > 0", value)?;
        }
        let spacing_factor = 2.0 * (f * (2.0 - f)).sqrt();
        let mut samples = Vec::new();
        for k in 0..lengths.len() {
            samples.push(TubeSample { u: k as f64, centre_of: Some(k) });
            if k + 1 == lengths.len() {
                break;
            }
            let spacing = 0.5 * (lengths[k] + lengths[k + 1]);
            let widest = spacing_factor * radii[k].min(radii[k + 1]);
            let per_segment = match groove_fraction {
                Some(_) => (spacing / widest).ceil().max(1.0) as usize,
                None => 1,
            };
            samples.extend((1..per_segment).map(|j| TubeSample {
                u: k as f64 + j as f64 / per_segment as f64,
                centre_of: None,
            }));
        }
        Ok(TubeSamples { samples })
    }

    /// The samples, head to tail.
    pub fn samples(&self) -> &[TubeSample] {
        &self.samples
    }

    /// The depth (cm) an edge may reach unseen between two samples a distance `spacing` apart
    /// on a tube of radius `radius`: r − √(r² − δ²/4) (module docs).
    pub fn groove_depth(spacing: f64, radius: f64) -> f64 {
        radius - (radius * radius - 0.25 * spacing * spacing).max(0.0).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_are_split_until_their_grooves_are_shallow_enough() {
        // ES103-like at 100 bodies: 0.424 cm bodies, radius 0.9 cm, a tapering tail of 0.2 cm.
        let lengths = [0.424; 4];
        let radii = [0.9, 0.9, 0.2, 0.2];
        let groove = Some(DEFAULT_GROOVE_FRACTION);
        let samples = TubeSamples::new(&lengths, &radii, groove).expect("valid");
        let beads = TubeSamples::new(&lengths, &radii, None).expect("valid");
        assert!(beads.samples().iter().enumerate().all(|(k, s)| s.centre_of == Some(k)));
        assert_eq!(beads.samples().len(), 4);
        let u: Vec<f64> = samples.samples().iter().map(|s| s.u).collect();
        // δ_max = 2r√(0.05·1.95) = 0.625 r: 0.562 cm at r = 0.9 (one sample), 0.125 cm at 0.2.
        assert_eq!(&u[..3], &[0.0, 1.0, 1.25]);
        assert_eq!(u.len(), 1 + 4 + 4 + 1);
        assert_eq!(samples.samples()[5].centre_of, Some(2));
        assert_eq!(samples.samples().last().map(|s| s.centre_of), Some(Some(3)));
        // Every groove is within the bound, and the next coarser split would not be.
        for k in 0..3 {
            let n = samples.samples().iter().filter(|s| s.u >= k as f64 && s.u < k as f64 + 1.0);
            let n = n.count() as f64;
            let r = f64::min(radii[k], radii[k + 1]);
            let depth = |n: f64| TubeSamples::groove_depth(0.424 / n, r) / r;
            assert!(depth(n) <= DEFAULT_GROOVE_FRACTION + 1e-15, "segment {k}: {}", depth(n));
            assert!(n == 1.0 || depth(n - 1.0) > DEFAULT_GROOVE_FRACTION, "segment {k}");
        }
    }

    #[test]
    fn bad_inputs_are_refused() {
        for f in [0.0, -0.1, 1.5, f64::NAN] {
            assert!(TubeSamples::new(&[1.0, 1.0], &[0.2, 0.2], Some(f)).is_err(), "{f}");
        }
        assert!(TubeSamples::new(&[1.0, 1.0], &[0.2], Some(0.05)).is_err());
        assert!(TubeSamples::new(&[1.0, 0.0], &[0.2, 0.2], None).is_err());
        assert!(TubeSamples::new(&[1.0, 1.0], &[0.2, f64::INFINITY], Some(0.05)).is_err());
    }
}
