//! The measured biometrics of one specimen, as stored in a RON data file
//! (`data/hagfish/es103.ron`). Field names carry their units (CGS, degrees).

use serde::{Deserialize, Serialize};

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
    /// Spring stiffness of each universal (bending) DOF of a chain of
    /// [`reference_body_count`](Self::reference_body_count) bodies (dyn·cm/rad), ≥ 0.
    pub bending_stiffness_dyn_cm_per_rad: f64,
    /// Spring stiffness of each revolute (twist) DOF of a chain of
    /// [`reference_body_count`](Self::reference_body_count) bodies (dyn·cm/rad), ≥ 0.
    pub twist_stiffness_dyn_cm_per_rad: f64,
    /// Damping of every DOF of a chain of [`reference_body_count`](Self::reference_body_count)
    /// bodies (dyn·cm·s/rad), ≥ 0.
    pub damping_dyn_cm_s_per_rad: f64,
    /// The number of bodies N_ref the per-joint values (stiffness, damping, limits) were given
    /// for: the thesis' 100 (the default). A chain of N bodies gets them scaled so that the
    /// animal stays the same and only the resolution changes (D16,
    /// [`Biometrics::resolution_scale`]); in `2..=`[`MAX_BODY_COUNT`].
    #[serde(default = "thesis_body_count")]
    pub reference_body_count: usize,
    /// Number N of rigid bodies (= joints, root included), in `2..=`[`MAX_BODY_COUNT`].
    pub body_count: usize,
    /// Optional taper of the radius beyond the last mark; `None` (the default) holds the
    /// last-mark radius to the tail tip.
    #[serde(default)]
    pub tail_taper: Option<TailTaper>,
    /// Optional compressible skin over the body (docs/physics.md, "Skin"); `None` (the
    /// default) makes the whole radius a rigid tube.
    #[serde(default)]
    pub skin: Option<BodySkin>,
}

/// A compressible outer layer of the body, the loose skin over the subcutaneous sinus
/// (docs/physics.md, "Skin"): contacts compress it down to the core (the notochord and muscle),
/// against the pressure of the fluid under it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySkin {
    /// The layer's thickness as a fraction of the local radius, in (0, 1): the core radius is
    /// `(1 − thickness_fraction)·r`.
    pub thickness_fraction: f64,
    /// The pressure of the fluid under the skin (dyn/cm²), > 0: two tubes crossing with their
    /// skins compressed by δ in all push apart with `π·p·√(r_a r_b)·δ`.
    pub pressure_dyn_per_cm2: f64,
}

/// A linear taper of the radius from its value at the last mark to `tip_radius_cm` at the
/// tail tip (s = L), for the paddle-shaped tail (docs/physics.md, "Body").
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TailTaper {
    /// Radius at the tail tip (cm), > 0.
    pub tip_radius_cm: f64,
}

/// The thesis' chain: 100 bodies (§4.1), for which its per-joint values were set.
pub const THESIS_BODY_COUNT: usize = 100;

fn thesis_body_count() -> usize {
    THESIS_BODY_COUNT
}

impl Biometrics {
    /// `N / N_ref`: how many joints of this chain share the stretch of body one joint of the
    /// reference chain covers (D16). Joints of one type sit 2ℓ apart, so the continuum
    /// stiffness is `B = k·2ℓ`, the internal damping `η = d·2ℓ` and the largest curvature
    /// `κ_max = θ/(2ℓ)`: keeping them as N changes means `k` and `d` times this scale and
    /// `θ` divided by it.
    pub fn resolution_scale(&self) -> f64 {
        self.body_count as f64 / self.reference_body_count as f64
    }

    /// The spring of each bending DOF of this chain, `k_b·N/N_ref` (dyn·cm/rad).
    pub fn joint_bending_stiffness(&self) -> f64 {
        self.bending_stiffness_dyn_cm_per_rad * self.resolution_scale()
    }

    /// The spring of each twist DOF of this chain, `k_t·N/N_ref` (dyn·cm/rad).
    pub fn joint_twist_stiffness(&self) -> f64 {
        self.twist_stiffness_dyn_cm_per_rad * self.resolution_scale()
    }

    /// The damper of every DOF of this chain, `d·N/N_ref` (dyn·cm·s/rad).
    pub fn joint_damping(&self) -> f64 {
        self.damping_dyn_cm_s_per_rad * self.resolution_scale()
    }

    /// A joint limit of this chain from one given for the reference chain: `θ·N_ref/N` (deg),
    /// at most [`MAX_JOINT_LIMIT_DEG`] (a chain much coarser than the reference one then bends
    /// less sharply than the animal: ES103's 75° reaches it below 42 bodies).
    pub fn joint_limit_deg(&self, reference_deg: f64) -> f64 {
        (reference_deg / self.resolution_scale()).min(MAX_JOINT_LIMIT_DEG)
    }
}

/// The largest joint limit a chain gets (deg), within the (0°, 180°) a body file may give.
pub const MAX_JOINT_LIMIT_DEG: f64 = 179.0;

/// The largest accepted [`Biometrics::body_count`]: a guard against absurd allocations from
/// a mistyped file (the thesis uses 100). A model this large builds in a fraction of a second;
/// whether its step buffers fit in the machine's memory is checked before they are allocated
/// (`hagfish_sim::check_memory`: about 10 000 bodies fit in 24 GB today).
pub const MAX_BODY_COUNT: usize = 100_000;
