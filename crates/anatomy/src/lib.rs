//! # hagfish-anatomy
//!
//! Hagfish biometrics (a RON data file, `data/hagfish/es103.ron`) turned into a
//! kinematic-tree model (`hagfish-tree`), in CGS units: cm, g, s, dyn·cm (`docs/physics.md`
//! D1, D5–D8).
//!
//! - [`Biometrics`] is the file's content; [`Biometrics::load`] parses and validates it, and
//!   every error ([`AnatomyError`]) says `file:line:column: what`.
//! - [`Biometrics::body_table`] derives N bodies of length ℓ = L/N: radius r = C/2π
//!   piecewise linear through the marks ([`interpolate_clamped`]), mass m_i = ρπr_i²ℓ with
//!   ρ chosen so Σ m_i = M, and per-joint limits (±twist on revolutes, ±θ(s) on both DOFs
//!   of universals).
//! - [`Rod`] is a uniform elastic rod (`data/rods/thin.ron`) with joint springs derived from
//!   its bending and twist stiffness; [`Body`] is either kind, as a scenario names it.
//! - [`Biometrics::to_model`] builds the chain along +X: alternating X-revolute /
//!   YZ-universal joints, root anchored at the world origin, solid-cylinder inertias
//!   ([`cylinder_inertia`]), gravity off.
//!
//! ```
//! use hagfish_anatomy::Body;
//!
//! // A rod 10 cm long in 20 bodies; its joint springs come from B and C over 2ℓ.
//! let text = r#"Rod(name: "demo", length_cm: 10.0, radius_cm: 0.05, body_count: 20,
//!     density_g_per_cm3: 1.0, bending_stiffness_dyn_cm2: 100.0,
//!     twist_stiffness_dyn_cm2: 66.7)"#;
//! let body = Body::from_ron(text.as_bytes(), std::path::Path::new("demo.ron"))?;
//! let model = body.to_model()?;
//! assert_eq!(model.body_count(), 20);
//! assert_eq!(model.dof_count(), 30); // 10 twist + 10 × 2 bend
//! assert!((body.mass_g() - std::f64::consts::PI * 0.05 * 0.05 * 10.0).abs() < 1e-12);
//! // A bad value is an error at its line and column, not a panic.
//! let bad = text.replace("100.0", "-1.0");
//! let bad = Body::from_ron(bad.as_bytes(), std::path::Path::new("b.ron"));
//! assert!(bad.unwrap_err().to_string().contains("b.ron:2:"));
//! # Ok::<(), hagfish_anatomy::AnatomyError>(())
//! ```

mod biometrics;
mod body;
mod error;
mod load;
mod locate;
mod model;
mod profile;
mod rod;
mod segment_chain;
mod table;
mod validate;

pub use biometrics::{
    Biometrics, BodySkin, MAX_BODY_COUNT, MAX_JOINT_LIMIT_DEG, THESIS_BODY_COUNT, TailTaper,
};
pub use body::Body;
pub use error::{AnatomyError, Field, Origin};
pub use load::{DataFile, MAX_DATA_FILE_BYTES, read_bounded, read_data_file};
pub use model::cylinder_inertia;
pub use profile::interpolate_clamped;
pub use rod::Rod;
pub use segment_chain::segment_chain;
pub use table::{BodyRow, BodyTable, LimitDeg, joint_kind};
