//! Pure geometry of the hagfish body: the Catmull-Rom centreline through the body
//! centres, self-contact detection on the tube around it, and wall contacts.
//!
//! The crate knows nothing about joints or masses. It takes body centres (cm, as
//! [`glam::DVec3`]) and radii and returns contact records that carry everything the solver
//! needs to build its rows: gaps, normals, tangents and the fixed weights of the real
//! bodies whose blend is each contact point (docs/physics.md, "Constraint rows").
//!
//! Pipeline of one step:
//!
//! 1. [`Centreline::update`] copies the centres and radii and rebuilds the arc-length table;
//! 2. [`ContactDetector::detect`] runs the [`BroadPhase`] (parry3d bounding spheres per
//!    body), the Newton [`closest_points`] search on the spline segments around each
//!    candidate body pair (thesis Eq. 4.5), and merges duplicate records into
//!    [`SelfContact`]s sorted head to tail;
//! 3. [`Wall::contacts`] lists the bodies near the wall as [`WallContact`]s, and
//!    [`Obstacle::contacts`] the points of the tube's [`TubeSamples`] near an obstacle.
//!
//! Per-step functions reuse the buffers of their workspaces and write into caller-owned
//! `Vec`s, so they do not allocate after the first call. Outputs are sorted over total
//! orders, so results are deterministic. Units are CGS (cm).
//!
//! A hairpin: a tube of radius 0.52 cm folded back on itself with its centreline strands 1 cm
//! apart, so the tubes overlap by 0.04 cm along the straight parts.
//!
//! ```
//! use glam::DVec3;
//! use hagfish_geometry::{Centreline, ContactDetector, DetectorOptions};
//!
//! let out = (0..20).map(|k| DVec3::new(0.5 * k as f64, 0.0, 0.0));
//! let turn = (1..6).map(|k| {
//!     let a = std::f64::consts::PI * k as f64 / 6.0;
//!     DVec3::new(9.5 + 0.5 * a.sin(), 0.5 - 0.5 * a.cos(), 0.0)
//! });
//! let back = (0..20).map(|k| DVec3::new(9.5 - 0.5 * k as f64, 1.0, 0.0));
//! let centres: Vec<DVec3> = out.chain(turn).chain(back).collect();
//! let radii = vec![0.52; centres.len()];
//! let centreline = Centreline::new(&centres, &radii)?;
//! let mut detector = ContactDetector::new(DetectorOptions::default())?;
//! let mut contacts = Vec::new();
//! detector.detect(&centreline, &vec![0.5; centres.len()], &mut contacts)?;
//! assert!(!contacts.is_empty());
//! for contact in &contacts {
//!     assert!((contact.gap + 0.04).abs() < 1e-3, "gap {}", contact.gap);
//!     assert!(contact.normal.y.abs() > 0.99, "the strands touch across y");
//! }
//! # Ok::<(), hagfish_geometry::GeometryError>(())
//! ```

mod arc_length;
mod broad_phase;
mod centreline;
mod chord;
mod cluster;
mod contact;
mod coverage;
mod detector;
mod error;
mod narrow_phase;
mod nearby;
mod obstacle;
mod obstacle_path;
mod obstacle_spin;
mod pair_blocks;
mod pair_queue;
mod pruning;
mod sampled_segment;
mod searches;
mod seeds;
mod segment;
mod segment_pairs;
mod tube_samples;
mod wall;
mod weights;

pub use broad_phase::{BroadPhase, BroadPhaseOptions};
pub use centreline::Centreline;
pub use cluster::CoarserClusters;
pub use contact::SelfContact;
pub use detector::{ContactDetector, DetectionReport, DetectorOptions, PAIRS_PER_BODY};
pub use error::GeometryError;
pub use narrow_phase::{
    ClosestPoints, GRADIENT_TOLERANCE, MAX_NEWTON_ITERATIONS, NewtonStatus, closest_points,
    closest_points_within,
};
pub use nearby::{NearbyClosestPoints, closest_points_near};
pub use obstacle::Obstacle;
pub use obstacle_path::{MovingObstacle, ObstaclePath};
pub use obstacle_spin::Spin;
pub use segment::Segment;
pub use tube_samples::{DEFAULT_GROOVE_FRACTION, TubeSample, TubeSamples};
pub use wall::{Wall, WallContact, WallOptions};
pub use weights::SplineWeights;
