//! The measured biometrics of one specimen, as stored in a RON data file
//! (`data/hagfish/es103.ron`). Field names carry their units (CGS, degrees).

use serde::Deserialize;

/// Measured biometrics of one hagfish and the joint parameters of its model (thesis
/// Tables 3.1 and 6.1; `docs/physics.md` D1, D5–D8).
///
/// Every array is indexed by measurement mark: `circumferences_cm[k]` and
/// `bending_limits_deg[k]` were measured at arc length `mark_fractions[k] · length_cm` from
/// the head. Load it with [`Biometrics::load`] (which also validates it) and turn it into a
/// model with [`Biometrics::to_model`] or a table with [`Biometrics::body_table`].
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Biometrics {
    /// Specimen label, e.g. "ES103".
    pub specimen: String,
    /// Total body length L, head to tail tip (cm), > 0.
    pub length_cm: f64,
    /// Total body mass M (g), > 0; the derived body masses sum to it exactly (D5).
    pub mass_g: f64,
    /// Arc-length positions of the marks as fractions of L, strictly increasing in (0, 1).
    pub mark_fractions: Vec<f64>,
    /// Circumference C at each mark (cm), > 0; radius r = C / 2π (D5).
    pub circumferences_cm: Vec<f64>,
    /// Symmetric bending limit θ at each mark (deg), in (0°, 180°) (D6).
    pub bending_limits_deg: Vec<f64>,
    /// Symmetric twist limit per revolute joint (deg), in (0°, 180°) (D7).
    pub twist_limit_deg: f64,
    /// Spring stiffness of each universal (bending) DOF (dyn·cm/rad), ≥ 0.
    pub bending_stiffness_dyn_cm_per_rad: f64,
    /// Spring stiffness of each revolute (twist) DOF (dyn·cm/rad), ≥ 0.
    pub twist_stiffness_dyn_cm_per_rad: f64,
    /// Damping of every DOF (dyn·cm·s/rad), ≥ 0.
    pub damping_dyn_cm_s_per_rad: f64,
    /// Number N of rigid bodies (= joints, root included), in `2..=`[`MAX_BODY_COUNT`].
    pub body_count: usize,
    /// Optional taper of the radius beyond the last mark; `None` (the default) holds the
    /// last-mark radius to the tail tip.
    #[serde(default)]
    pub tail_taper: Option<TailTaper>,
}

/// A linear taper of the radius from its value at the last mark to `tip_radius_cm` at the
/// tail tip (s = L), for the paddle-shaped tail (docs/physics.md, "Body").
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TailTaper {
    /// Radius at the tail tip (cm), > 0.
    pub tip_radius_cm: f64,
}

/// The largest accepted [`Biometrics::body_count`]: a guard against absurd allocations from
/// a mistyped file (the thesis uses 100). A model this large builds in a fraction of a second;
/// whether its step buffers fit in the machine's memory is checked before they are allocated
/// (`hagfish_sim::check_memory`: about 10 000 bodies fit in 24 GB today).
pub const MAX_BODY_COUNT: usize = 100_000;
