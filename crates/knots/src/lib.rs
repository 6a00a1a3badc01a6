//! Knot type of an open centreline — has the hagfish tied a knot in its body, which one, and
//! where along the body is it?
//!
//! An open curve is always unknotted in the strict sense; what is meant is the knot formed
//! when its ends are joined "far away". [`analyse_knot`] does this along many directions:
//!
//! 1. **Normalise** (`closure.rs`): translate to the bounding-box centre and scale to unit
//!    diameter, so the result does not depend on position or units (cm or m).
//! 2. **Close** each of `directions` quasi-uniform unit vectors d (Fibonacci sphere): both
//!    ends go straight along d to the plane at [`CLOSURE_DISTANCE`] diameters beyond the
//!    centre, where the two far points are joined.
//! 3. **Project** (`projection.rs`) the closed polygon along a view tilted 1 rad from d and
//!    collect the crossings (f64 geometry; a projection that is not generic within a margin
//!    of 10⁻⁹ diameters is rejected and another view tried, up to 8).
//! 4. **Alexander polynomial** (`alexander.rs`): label the c arcs between under-passes,
//!    build the c×c Alexander matrix with rows `1 − t` (over-arc), `t` / `−1` (incoming /
//!    outgoing under-arc, swapped for negative crossings), delete one row and column, and
//!    take the determinant exactly (`determinant.rs`, `modular.rs`): the pencil A + tB is
//!    expanded through the characteristic polynomial of (A + B)⁻¹B over 𝔽ₚ, p = 2⁶¹ − 1,
//!    in O(c³), and the residues are read as integers in (−p/2, p/2]. The result is
//!    ±tᵏΔ(t) of degree ≤ c − 1; it is normalised to Δ(0) > 0 ([`AlexanderPolynomial`])
//!    and checked to be palindromic with |Δ(1)| = 1. The polynomial depends only on the
//!    diagram's arc labels and signs, so it is remembered by them (`memo.rs`): a vote, and
//!    the frames of a run analysed by one [`KnotAnalyser`], meet the same diagrams again.
//! 5. **Vote**: the most frequent polynomial wins (ties to the simpler); `agreement` is its
//!    share. Directions whose rays pierce the knotted region are the minority when the
//!    ends stick out of it.
//! 6. **Name** it ([`KnotType`], prime knots up to 6 crossings) and optionally locate the
//!    **extent** (`extent.rs`): the smallest sub-arc whose own closure keeps the type, by a
//!    binary search per end with `extent_directions` directions per vote; each of those
//!    votes stops once the remaining directions cannot change whether the type wins.
//!
//! Limits: the Alexander polynomial does not see chirality and misses a few knots (e.g.
//! Δ = 1 for the Conway and Kinoshita–Terasaka knots); a polynomial with a coefficient
//! beyond ≈ 1.15·10¹⁸ in magnitude is not recovered (caught by the palindrome / Δ(1) check:
//! that direction abstains). No Reidemeister simplification is done, so c includes the
//! crossings of the closure rays.
//!
//! Cost per direction: O(n²) edge pairs (bounding boxes first) plus O(c³) for the
//! determinant. For the 100-vertex hagfish-like trefoil (c ≤ 9) that is ≈ 7 µs, so a
//! 64-direction vote (the default) takes ≈ 0.35 ms (`benches/knot_type.rs`); a random 100-vertex walk
//! crammed into a 1 cm ball (c up to ≈ 270) takes ≈ 10 ms per direction.
//!
//! ```
//! use glam::DVec3;
//! use hagfish_knots::{KnotOptions, analyse_knot};
//!
//! // A trefoil drawn as an open polyline: the (2,3) torus knot, cut open and its ends pulled
//! // out along ±z.
//! let mut points: Vec<DVec3> = (0..=120)
//!     .map(|k| {
//!         let t = 0.1 + (std::f64::consts::TAU - 0.2) * k as f64 / 120.0;
//!         let r = 2.0 + (3.0 * t).cos();
//!         DVec3::new(r * (2.0 * t).cos(), r * (2.0 * t).sin(), (3.0 * t).sin())
//!     })
//!     .collect();
//! points.insert(0, points[0] - DVec3::new(0.0, 0.0, 10.0));
//! points.push(points[points.len() - 1] + DVec3::new(0.0, 0.0, 10.0));
//! let report = analyse_knot(&points, &KnotOptions::default())?;
//! assert_eq!(report.knot.to_string(), "3_1");
//! assert!(report.agreement > 0.9);
//! # Ok::<(), hagfish_knots::KnotError>(())
//! ```

mod alexander;
mod analysis;
mod closure;
mod determinant;
mod directions;
mod error;
mod extent;
mod knot_type;
mod memo;
mod modular;
mod options;
mod polynomial;
mod projection;
mod report;
mod vote;

pub use analysis::{KnotAnalyser, MIN_OPEN_POINTS, analyse_knot, closed_polygon_polynomial};
pub use closure::CLOSURE_DISTANCE;
pub use error::KnotError;
pub use knot_type::KnotType;
pub use options::KnotOptions;
pub use polynomial::AlexanderPolynomial;
pub use projection::MAX_CROSSINGS;
pub use report::KnotReport;
