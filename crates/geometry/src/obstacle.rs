//! Rigid obstacles: planes, spheres and cylinders posed in space, touched by the body's tube at
//! the points of its [`TubeSamples`] (the body centres and, where the bodies are long against
//! their radius, spline points between them), each a sphere of the tube's radius r(u) there.
//!
//! For a sample point x the obstacle gives the signed distance d(x) from its surface (positive
//! outside) and the outward unit normal n(x) at the nearest surface point; the contact record
//! is the wall's, gap d(x) − r(u) and normal n(x), so the wall's rows (and their friction)
//! serve every obstacle:
//! - plane through p with normal n: d = n·(x − p);
//! - sphere of centre C and radius R: d = |x − C| − R, n = (x − C)/|x − C|;
//! - cylinder of axis point P, unit axis a and radius R, infinite or of half-length H about P:
//!   with x − P = s a + ρ (ρ ⊥ a), d = |ρ| − R and n = ρ/|ρ| on the mantle; past a cap
//!   (|s| > H) d = |s| − H with n = sign(s) a over the cap's disc (|ρ| ≤ R), and beyond its rim
//!   the distance to the rim circle.

use glam::{DQuat, DVec3};

use crate::centreline::Centreline;
use crate::error::GeometryError;
use crate::tube_samples::TubeSamples;
use crate::wall::WallContact;

/// A rigid obstacle (module docs). Built by [`Obstacle::plane`], [`Obstacle::sphere`] or
/// [`Obstacle::cylinder`], which check their numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Obstacle {
    /// The half-space behind a plane.
    Plane {
        /// A point of the plane (cm).
        point: DVec3,
        /// Unit normal toward the free side.
        normal: DVec3,
    },
    /// A solid sphere.
    Sphere {
        /// Centre (cm).
        centre: DVec3,
        /// Radius (cm).
        radius: f64,
    },
    /// A solid circular cylinder.
    Cylinder {
        /// A point of the axis, the middle of a finite cylinder (cm).
        point: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Radius (cm).
        radius: f64,
        /// Half of the length (cm), `None` for an infinite cylinder.
        half_length: Option<f64>,
    },
}

impl Obstacle {
    /// The plane through `point` with normal `normal` (normalised here) toward the free side.
    pub fn plane(point: DVec3, normal: DVec3) -> Result<Self, GeometryError> {
        Ok(Obstacle::Plane { point: finite_point(point)?, normal: unit(normal, "plane normal")? })
    }

    /// The sphere of centre `centre` and radius `radius` (> 0).
    pub fn sphere(centre: DVec3, radius: f64) -> Result<Self, GeometryError> {
        Ok(Obstacle::Sphere { centre: finite_point(centre)?, radius: positive(radius, "radius")? })
    }

    /// The cylinder about the axis through `point` along `axis` (normalised here) of radius
    /// `radius` (> 0), infinite or of half-length `half_length` (> 0).
    pub fn cylinder(
        point: DVec3,
        axis: DVec3,
        radius: f64,
        half_length: Option<f64>,
    ) -> Result<Self, GeometryError> {
        let half_length = half_length.map(|h| positive(h, "half length")).transpose()?;
        Ok(Obstacle::Cylinder {
            point: finite_point(point)?,
            axis: unit(axis, "cylinder axis")?,
            radius: positive(radius, "radius")?,
            half_length,
        })
    }

    /// The obstacle moved by `offset` (cm): its point or centre shifted, its directions kept.
    pub fn translated(&self, offset: DVec3) -> Obstacle {
        match *self {
            Obstacle::Plane { point, normal } => Obstacle::Plane { point: point + offset, normal },
            Obstacle::Sphere { centre, radius } => {
                Obstacle::Sphere { centre: centre + offset, radius }
            }
            Obstacle::Cylinder { point, axis, radius, half_length } => {
                Obstacle::Cylinder { point: point + offset, axis, radius, half_length }
            }
        }
    }

    /// The obstacle turned by `rotation` about `pivot`: its point or centre carried round the
    /// pivot, its directions turned.
    pub fn rotated_about(&self, rotation: DQuat, pivot: DVec3) -> Obstacle {
        let carried = |x: DVec3| pivot + rotation * (x - pivot);
        match *self {
            Obstacle::Plane { point, normal } => {
                Obstacle::Plane { point: carried(point), normal: rotation * normal }
            }
            Obstacle::Sphere { centre, radius } => {
                Obstacle::Sphere { centre: carried(centre), radius }
            }
            Obstacle::Cylinder { point, axis, radius, half_length } => Obstacle::Cylinder {
                point: carried(point),
                axis: rotation * axis,
                radius,
                half_length,
            },
        }
    }

    /// The point a turn is about ([`crate::Spin`]): the plane's point, the sphere's centre, the
    /// cylinder's axis point.
    pub fn reference_point(&self) -> DVec3 {
        match *self {
            Obstacle::Plane { point, .. } | Obstacle::Cylinder { point, .. } => point,
            Obstacle::Sphere { centre, .. } => centre,
        }
    }

    /// The signed distance of `c` from the surface (cm, negative inside) and the outward unit
    /// normal at the nearest surface point (module docs).
    pub fn distance(&self, c: DVec3) -> (f64, DVec3) {
        match *self {
            Obstacle::Plane { point, normal } => (normal.dot(c - point), normal),
            Obstacle::Sphere { centre, radius } => {
                let v = c - centre;
                (v.length() - radius, v.try_normalize().unwrap_or(DVec3::Z))
            }
            Obstacle::Cylinder { point, axis, radius, half_length } => {
                let v = c - point;
                let along = v.dot(axis);
                let radial = v - along * axis;
                let out = radial.try_normalize().unwrap_or_else(|| axis.any_orthonormal_vector());
                let beyond = half_length.map_or(0.0, |h| along.abs() - h);
                if beyond <= 0.0 {
                    return (radial.length() - radius, out);
                }
                let cap = along.signum() * axis;
                if radial.length() <= radius {
                    return (beyond, cap);
                }
                let rim = point + (along - along.signum() * beyond) * axis + radius * out;
                let to_rim = c - rim;
                (to_rim.length(), to_rim.try_normalize().unwrap_or(cap))
            }
        }
    }

    /// Appends to `out` a contact record for every sample of `samples` (of `centreline`'s
    /// body) whose sphere lies within `margin` of the obstacle: gap d(x(u)) − r(u) and normal
    /// n(x(u)), head to tail. A sample at a body's centre is that body's sphere, as the wall's.
    pub fn contacts(
        &self,
        centreline: &Centreline,
        samples: &TubeSamples,
        margin: f64,
        out: &mut Vec<WallContact>,
    ) {
        let (centres, radii) = (centreline.centres(), centreline.radii());
        for sample in samples.samples() {
            let (point, radius) = match sample.centre_of {
                Some(body) => (centres[body], radii[body]),
                None => (centreline.point(sample.u), centreline.radius(sample.u)),
            };
            let (distance, normal) = self.distance(point);
            let gap = distance - radius;
            if gap < margin {
                out.push(match sample.centre_of {
                    Some(body) => WallContact::of_body(body, (point, radius), gap, normal),
                    None => WallContact {
                        u: sample.u,
                        weights: centreline.weights(sample.u),
                        point,
                        radius,
                        gap,
                        normal,
                        surface_velocity: DVec3::ZERO,
                    },
                });
            }
        }
    }
}

fn finite_point(point: DVec3) -> Result<DVec3, GeometryError> {
    GeometryError::require_option(point.is_finite(), "obstacle point", "finite", point.length())?;
    Ok(point)
}

fn unit(v: DVec3, name: &'static str) -> Result<DVec3, GeometryError> {
    v.try_normalize().ok_or(GeometryError::InvalidOption {
        name,
        requirement: "finite and non-zero",
        value: v.length(),
    })
}

fn positive(value: f64, name: &'static str) -> Result<f64, GeometryError> {
    GeometryError::require_option(value.is_finite() && value > 0.0, name, "finite and > 0", value)?;
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tube_samples::DEFAULT_GROOVE_FRACTION;

    #[test]
    fn distances_and_normals_of_each_shape() {
        let plane =
            Obstacle::plane(DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.0, 2.0, 0.0)).expect("plane");
        assert_eq!(plane.distance(DVec3::new(5.0, 1.0, 3.0)), (2.0, DVec3::Y));
        let sphere = Obstacle::sphere(DVec3::ZERO, 2.0).expect("sphere");
        let (d, n) = sphere.distance(DVec3::new(0.0, 0.0, 3.0));
        assert!((d - 1.0).abs() < 1e-15 && n == DVec3::Z);
        let infinite = Obstacle::cylinder(DVec3::ZERO, DVec3::Z, 1.0, None).expect("cylinder");
        let (d, n) = infinite.distance(DVec3::new(3.0, 0.0, 100.0));
        assert!((d - 2.0).abs() < 1e-15 && (n - DVec3::X).length() < 1e-15);
        let finite = Obstacle::cylinder(DVec3::ZERO, DVec3::Z, 1.0, Some(2.0)).expect("cylinder");
        // Mantle, cap, rim.
        let (d, n) = finite.distance(DVec3::new(0.0, 1.5, 1.0));
        assert!((d - 0.5).abs() < 1e-15 && (n - DVec3::Y).length() < 1e-15);
        let (d, n) = finite.distance(DVec3::new(0.5, 0.0, -3.0));
        assert!((d - 1.0).abs() < 1e-15 && n == -DVec3::Z);
        let (d, n) = finite.distance(DVec3::new(4.0, 0.0, 6.0));
        assert!((d - 5.0).abs() < 1e-14 && (n - DVec3::new(0.6, 0.0, 0.8)).length() < 1e-14);
        // Inside: negative.
        assert!(finite.distance(DVec3::new(0.2, 0.0, 0.5)).0 < 0.0);
    }

    #[test]
    fn bodies_within_the_margin_are_reported_in_order() {
        let centres: Vec<DVec3> = (0..6).map(|k| DVec3::new(f64::from(k), 0.0, 0.0)).collect();
        let line = Centreline::new(&centres, &[0.2; 6]).expect("a centreline");
        let sphere = Obstacle::sphere(DVec3::new(3.0, 0.7, 0.0), 0.5).expect("sphere");
        let mut out = Vec::new();
        // f = 1: samples 2r = 0.4 cm apart, so three per 1 cm segment.
        let samples = TubeSamples::new(&[1.0; 6], &[0.2; 6], Some(1.0)).expect("samples");
        sphere.contacts(&line, &samples, 0.05, &mut out);
        let at: Vec<_> = out.iter().map(|c| (c.u, c.body())).collect();
        assert_eq!(at, vec![(3.0, Some(3))], "the samples beside it are 0.36 cm from the sphere");
        assert!((out[0].gap - 0.0).abs() < 1e-15 && (out[0].normal + DVec3::Y).length() < 1e-15);
    }

    /// A thin pole (radius 0.05 cm) across a straight chain of 1 cm bodies of radius 0.3 cm,
    /// midway between two centres and 0.3 cm from the axis: the tube overlaps it by 0.05 cm.
    /// The bodies' spheres alone clear it by 0.233 cm; the default samples find it within the
    /// groove bound of the true depth, which a dense sampling of the axis gives.
    #[test]
    fn a_thin_pole_between_two_centres_is_found_within_the_groove_bound() {
        let centres: Vec<DVec3> = (0..8).map(|k| DVec3::new(f64::from(k), 0.0, 0.0)).collect();
        let line = Centreline::new(&centres, &[0.3; 8]).expect("a centreline");
        let pole =
            Obstacle::cylinder(DVec3::new(3.5, 0.3, 0.0), DVec3::Z, 0.05, None).expect("a pole");
        let sphere_gap = |x: DVec3| pole.distance(x).0 - 0.3;
        let nearest_centre = sphere_gap(centres[3]).min(sphere_gap(centres[4]));
        assert!(nearest_centre > 0.2, "the centres' spheres clear the pole: {nearest_centre}");
        let true_gap = (0..=7000)
            .map(|i| sphere_gap(line.point(f64::from(i) / 1000.0)))
            .fold(f64::INFINITY, f64::min);
        assert!((true_gap + 0.05).abs() < 1e-9, "the tube overlaps it by 0.05 cm: {true_gap}");
        let groove = Some(DEFAULT_GROOVE_FRACTION);
        let samples = TubeSamples::new(&[1.0; 8], &[0.3; 8], groove).expect("samples");
        let beads = TubeSamples::new(&[1.0; 8], &[0.3; 8], None).expect("samples");
        let mut missed = Vec::new();
        pole.contacts(&line, &beads, 0.0, &mut missed);
        assert!(missed.is_empty(), "the beads miss it: {missed:?}");
        let mut out = Vec::new();
        pole.contacts(&line, &samples, 0.0, &mut out);
        let deepest = out.iter().map(|c| c.gap).fold(f64::INFINITY, f64::min);
        assert!(deepest >= true_gap - 1e-12, "a sample is never deeper than the tube");
        assert!(deepest - true_gap <= DEFAULT_GROOVE_FRACTION * 0.3, "{deepest} vs {true_gap}");
        let between = out.iter().filter(|c| c.body().is_none() && c.u > 3.0 && c.u < 4.0);
        assert!(between.count() > 0, "{out:?}");
        for contact in &out {
            assert!(contact.point.distance(line.point(contact.u)) < 1e-15);
            let blend: DVec3 = contact.weights.iter().map(|(m, w)| w * centres[m]).sum();
            assert!(blend.distance(contact.point) < 1e-12, "the weights blend x(u)");
        }
    }

    #[test]
    fn bad_obstacles_are_refused() {
        assert!(Obstacle::plane(DVec3::ZERO, DVec3::ZERO).is_err());
        assert!(Obstacle::sphere(DVec3::ZERO, 0.0).is_err());
        assert!(Obstacle::sphere(DVec3::splat(f64::NAN), 1.0).is_err());
        assert!(Obstacle::cylinder(DVec3::ZERO, DVec3::X, 1.0, Some(-1.0)).is_err());
        assert!(Obstacle::cylinder(DVec3::ZERO, DVec3::ZERO, 1.0, None).is_err());
    }
}
