//! Contact between the bodies and the wall the head is attached to.
//!
//! The wall is the half-space boundary through p_w with unit normal n_w pointing into the
//! water (the body side). Each body is tested as a sphere of radius r_k at its centre,
//! with gap d_k = n_w·(c_k − p_w) − r_k; only the centre velocity enters
//! the row n_wᵀ R_k [0 I₃] J_k. The wall holds the head, so the bodies near it are the head's,
//! short against their radius: their spheres stand for the tube there (obstacles, which any
//! part of the body may touch, sample the tube between centres too: `tube_samples.rs`).

use glam::DVec3;

use crate::centreline::Centreline;
use crate::error::GeometryError;
use crate::weights::SplineWeights;

/// A point of the tube near or inside the wall or an obstacle (`obstacle.rs`): a body's sphere
/// (the wall's contacts) or a sphere of the tube's radius at a spline point between centres
/// (`tube_samples.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallContact {
    /// Spline parameter u of the point (the body index k at a body's centre).
    pub u: f64,
    /// The bodies and weights whose blend Σ w_m c_m is the point x(u): the weight 1 on body k
    /// alone at a centre.
    pub weights: SplineWeights,
    /// The tube's axis point x(u) (cm).
    pub point: DVec3,
    /// The tube's radius r(u) there (cm).
    pub radius: f64,
    /// Signed gap d = n·(x(u) − p) − r(u) for the wall (cm), the obstacle's distance less
    /// r(u) for an obstacle; negative when the tube penetrates.
    pub gap: f64,
    /// The unit normal of the surface at the point (pointing to the body side).
    pub normal: DVec3,
    /// The velocity of the surface (cm/s): zero for the wall and still obstacles, the path's
    /// for a moving one (`obstacle_path.rs`). The contact's rows bound the body's velocity
    /// relative to it.
    pub surface_velocity: DVec3,
}

impl WallContact {
    /// The contact of body `body`'s sphere (centre c, radius r) with gap `gap` along `normal`.
    pub fn of_body(body: usize, (centre, radius): (DVec3, f64), gap: f64, normal: DVec3) -> Self {
        WallContact {
            u: body as f64,
            weights: SplineWeights::single(body),
            point: centre,
            radius,
            gap,
            normal,
            surface_velocity: DVec3::ZERO,
        }
    }

    /// The body whose sphere this is, `None` for a point between centres.
    pub fn body(&self) -> Option<usize> {
        (self.weights.len == 1).then_some(self.weights.bodies[0])
    }
}

/// Options of a [`Wall`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallOptions {
    /// Bodies are reported when their gap is below this (cm, default 0.05).
    pub margin: f64,
    /// Bodies with a smaller index are never reported (default 0). The head and its
    /// neighbours touch the wall by construction: a caller that knows the
    /// body's rest shape sets this from [`Wall::first_clear_body`], so the exclusion follows
    /// the geometry (radii, segment length) rather than a fixed count.
    pub first_body: usize,
}

impl Default for WallOptions {
    fn default() -> Self {
        WallOptions { margin: 0.05, first_body: 0 }
    }
}

/// A planar wall with its contact options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    point: DVec3,
    normal: DVec3,
    options: WallOptions,
}

impl Wall {
    /// Creates a wall through `point` with normal `normal` (normalised here; it points to
    /// the body side).
    ///
    /// # Errors
    /// [`GeometryError::InvalidOption`] if `point` is not finite, `normal` is zero or not
    /// finite, or the margin is not finite (the value shown is the vector's length for
    /// vectors).
    pub fn new(point: DVec3, normal: DVec3, options: WallOptions) -> Result<Self, GeometryError> {
        GeometryError::require_option(point.is_finite(), "wall point", "finite", point.length())?;
        let normal = normal.try_normalize().ok_or(GeometryError::InvalidOption {
            name: "wall normal",
            requirement: "finite and non-zero",
            value: normal.length(),
        })?;
        GeometryError::require_option(
            options.margin.is_finite(),
            "wall margin",
            "finite",
            options.margin,
        )?;
        Ok(Wall { point, normal, options })
    }

    /// The wall's unit normal n_w.
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// Signed gap d = n_w·(c − p_w) − r of a sphere of radius `radius` at `centre` (cm).
    pub fn gap(&self, centre: DVec3, radius: f64) -> f64 {
        self.normal.dot(centre - self.point) - radius
    }

    /// The first body, counted from the head, whose sphere at `centres` (a rest shape) clears
    /// the wall by at least the margin: `min k` with d_k ≥ margin, or the body count if none
    /// does. The bodies before it touch the wall by construction and are not tested.
    pub fn first_clear_body(&self, centres: &[DVec3], radii: &[f64]) -> usize {
        centres
            .iter()
            .zip(radii)
            .position(|(&c, &r)| self.gap(c, r) >= self.options.margin)
            .unwrap_or(centres.len())
    }

    /// Fills `out` with the bodies k ≥ `first_body` of `centreline` whose gap is below
    /// the margin, in increasing body order (a pure function of its inputs).
    pub fn contacts(&self, centreline: &Centreline, out: &mut Vec<WallContact>) {
        out.clear();
        let bodies = centreline.centres().iter().zip(centreline.radii()).enumerate();
        out.extend(
            bodies
                .skip(self.options.first_body)
                .map(|(body, (&c, &r))| {
                    WallContact::of_body(body, (c, r), self.gap(c, r), self.normal)
                })
                .filter(|contact| contact.gap < self.options.margin),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall() -> Wall {
        Wall::new(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), WallOptions::default())
            .expect("valid wall")
    }

    #[test]
    fn first_clear_body_is_the_first_sphere_beyond_the_margin() {
        let w = wall(); // margin 0.05
        let radii = [0.9; 6];
        // Centres every 0.424 cm along +X from 0.212: gaps −0.688, −0.264, 0.16, 0.584, …
        let centres: Vec<DVec3> =
            (0..6).map(|k| DVec3::new(0.212 + 0.424 * k as f64, 0.0, 0.0)).collect();
        assert_eq!(w.first_clear_body(&centres, &radii), 2);
        // Shorter segments: more bodies start inside the margin.
        let short: Vec<DVec3> =
            (0..6).map(|k| DVec3::new(0.1 + 0.2 * k as f64, 0.0, 0.0)).collect();
        assert_eq!(w.first_clear_body(&short, &radii), 5);
        assert_eq!(w.first_clear_body(&short[..4], &radii[..4]), 4);
    }

    #[test]
    fn gap_is_positive_outside_zero_touching_negative_inside() {
        let w = wall();
        assert!((w.gap(DVec3::new(2.0, 5.0, 0.0), 0.5) - 1.5).abs() < 1e-15);
        assert_eq!(w.gap(DVec3::new(0.5, -1.0, 3.0), 0.5), 0.0);
        assert!((w.gap(DVec3::new(0.2, 0.0, 0.0), 0.5) + 0.3).abs() < 1e-15);
        assert!(w.gap(DVec3::new(-1.0, 0.0, 0.0), 0.5) < 0.0);
        assert_eq!(w.normal(), DVec3::X);
    }

    #[test]
    fn reports_bodies_within_margin_from_first_body_on() {
        // Bodies at x = 0, −1, 0.52, 3, 0.1: radius 0.5.
        let xs = [0.0, -1.0, 0.52, 3.0, 0.1, 0.54];
        let centres: Vec<_> = xs.iter().map(|&x| DVec3::new(x, 0.0, 0.0)).collect();
        let line = Centreline::new(&centres, &[0.5; 6]).expect("valid");
        let mut out = Vec::new();
        let options = WallOptions { first_body: 0, ..WallOptions::default() };
        Wall::new(DVec3::ZERO, DVec3::X, options).expect("valid").contacts(&line, &mut out);
        let bodies: Vec<_> = out.iter().filter_map(WallContact::body).collect();
        assert_eq!(bodies, vec![0, 1, 2, 4, 5]);
        assert!(out.iter().all(|c| c.normal == DVec3::X));
        let from_third = WallOptions { first_body: 3, ..WallOptions::default() };
        Wall::new(DVec3::ZERO, DVec3::X, from_third).expect("valid").contacts(&line, &mut out);
        let bodies: Vec<_> = out.iter().map(|c| (c.body(), c.gap < 0.0)).collect();
        assert_eq!(bodies, vec![(Some(4), true), (Some(5), false)]);
    }

    #[test]
    fn invalid_walls_are_rejected() {
        let options = WallOptions::default();
        assert!(Wall::new(DVec3::ZERO, DVec3::ZERO, options).is_err());
        assert!(Wall::new(DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0), options).is_err());
        assert!(Wall::new(DVec3::splat(f64::INFINITY), DVec3::X, options).is_err());
        let nan_margin = WallOptions { margin: f64::NAN, ..options };
        assert!(matches!(
            Wall::new(DVec3::ZERO, DVec3::X, nan_margin),
            Err(GeometryError::InvalidOption { name: "wall margin", .. })
        ));
    }
}
