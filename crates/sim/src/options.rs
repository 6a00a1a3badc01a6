//! Options of the step: time step, constraint stabilisation, margins, contact and wall set-up.

use glam::DVec3;
#[cfg(doc)]
use hagfish_geometry::TubeSamples;
use hagfish_geometry::{DEFAULT_GROOVE_FRACTION, DetectorOptions, MovingObstacle, WallOptions};
use hagfish_solver::{QpBackend, SolverOptions};
use hagfish_tree::Model;

use crate::acceptance::StepAcceptance;
use crate::backend::DynamicsBackend;
use crate::error::SimError;
use crate::rows::{ConeForm, Friction};

/// Cluster radius, in bodies, of self contacts at the chain's resolution: 1.5, the
/// body-relative radius of the 100-body ES103 (`contact_exclusion_diameters`). A finer chain
/// merges contacts over more bodies (4.7 at 300 bodies), and between two kept records of a
/// line contact it has joints free to bend into the other strand: on fine chains that is
/// where steps go deep (docs/physics.md, "Step acceptance and substeps").
pub const RESOLVED_CLUSTER_BODIES: f64 = 1.5;

/// The finest chain (bodies) whose retries resolve contacts at [`RESOLVED_CLUSTER_BODIES`]:
/// 300, the finest the retry was measured on. A chain of N > 300 bodies retries at
/// 1.5·N/300 bodies, the same length of body. A retry's rows grow about with the square of
/// its refinement over the body-relative radius (records merge in both spline parameters)
/// and its contact-space solve with their cube: ES103 at 1000 bodies (body-relative radius
/// 15.75 bodies) retried at 1.5 bodies carried ≈ 3600 rows and `thesis.ron` there fell to
/// 5 steps per second; retried at 5 it completes (docs/physics.md, "Step acceptance and
/// substeps").
pub const FINEST_RESOLVED_CHAIN: usize = 300;

/// Everything that shapes a step but is not the body itself. Immutable during a run.
#[derive(Debug, Clone, PartialEq)]
pub struct StepOptions {
    /// Time step h (s), default 0.01 (`docs/physics.md` D2).
    pub time_step: f64,
    /// Fraction of a bilateral (head) error corrected per step: `b = −(β/h)·error`.
    pub head_correction: f64,
    /// Fraction β of a penetration (negative gap) pushed out per step: `b = −(β/h)·d` for
    /// d < 0. Default 1 (full correction; `docs/physics.md` explains why not 0.2).
    pub push_out: f64,
    /// A joint-limit row is added when the gap to the limit is below
    /// `max(min(limit_margin, range/4), 2h|q̇|)` (rad; range = upper − lower).
    pub limit_margin: f64,
    /// Whether self contact is detected and enforced.
    pub self_contact: bool,
    /// Self-contact detection options (speculative margin: default 0.1 cm, so approach speeds
    /// up to 10 cm/s at h = 0.01 s are caught a step early; 0.2 cm gave the same penetration in
    /// `form.ron` and a 10 % slower knotted step). Its chain-index gap and cluster radius are
    /// replaced by the body-relative rule of [`StepOptions::contact_exclusion_diameters`] when
    /// the step data is built for a model.
    pub contact: DetectorOptions,
    /// Self contacts between points of the body closer than this many (largest) diameters of
    /// arc length are ignored: a straight tube touches itself up to one diameter away, so
    /// neighbouring parts always "overlap". Default 2, which is the 8 bodies of the 100-body
    /// ES103 (2 · 1.78 cm / 0.424 cm = 8.4); contacts closer than 3/16 of that gap in both spline
    /// parameters are merged as one. In bodies: `index_gap = max(2, round(k·D_max/ℓ_min))`.
    pub contact_exclusion_diameters: f64,
    /// The wall: a point on it (cm) and its normal toward the body; `None` for no wall.
    pub wall: Option<(DVec3, DVec3)>,
    /// Wall contact options (first body tested; margin 0.2 cm by default).
    pub wall_options: WallOptions,
    /// Options of the velocity solve (QP backend, tolerances).
    pub solver: SolverOptions,
    /// Fixed-point iterations that re-evaluate the velocity-product force at the new
    /// velocity (0: explicit, as REDMAX). Default 1: explicit terms make the ES103 chain
    /// unstable at h = 0.01 s once runs of joints lock at their limits (`docs/physics.md`).
    pub velocity_product_iterations: usize,
    /// The linear algebra of the velocity step: sparse maximal (default; linear in the number
    /// of bodies) or dense reduced (the reference; `docs/physics.md`). Same answer up to
    /// rounding.
    pub backend: DynamicsBackend,
    /// Contact prediction (`contact_prediction.rs`): after a solve, the self-contact gaps at
    /// `q + h q̇` are evaluated exactly, and the bound of every row whose gap would end more than
    /// this tolerance (cm) below its target is raised and the step solved again. `None`: off
    /// (first-order rows only). Default 0.001 cm (≈ 0.2 % of the radius).
    pub contact_prediction: Option<f64>,
    /// When a step's result is accepted ([`StepAcceptance`]).
    pub acceptance: StepAcceptance,
    /// Coulomb friction on the self contacts (their cores), the wall and the obstacles, by the
    /// inscribed pyramid of the friction cone or the cone itself ([`crate::rows::ConeForm`];
    /// docs/physics.md, "Friction: the cone and its pyramid");
    /// `None` (default) or μ = 0: frictionless, as the thesis.
    pub friction: Option<Friction>,
    /// Rigid obstacles (planes, spheres, cylinders), still or moving on a path, that the
    /// bodies touch as they touch the wall: their contacts join the wall's
    /// (`StepData::wall_contacts`), with the wall's margin, rows, friction and acceptance bound
    /// (docs/physics.md, "Obstacles"). Default none.
    pub obstacles: Vec<MovingObstacle>,
    /// How finely obstacles see the tube: the deepest groove an obstacle's edge may reach
    /// unseen between two of the points they touch, as a fraction f of the local radius
    /// (in (0, 1], default [`DEFAULT_GROOVE_FRACTION`] = 0.05): segments whose bodies are long
    /// against their radius are sampled between their centres ([`TubeSamples`],
    /// docs/physics.md, "Obstacles"). `None`: the bodies' spheres alone, a chain of beads.
    pub obstacle_groove: Option<f64>,
    /// Whether the head rows hold the root joints at their rest values (default
    /// [`RootHold::Held`], the hagfish's head at the wall) or leave them free.
    pub root: RootHold,
}

/// What the head rows (`docs/physics.md` D9) do with the root joints' DOFs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RootHold {
    /// Every root DOF is held at its rest value: the head fixed at the wall.
    #[default]
    Held,
    /// No head rows: a root free to move as its joint allows (a
    /// [`Translation`](hagfish_tree::JointKind::Translation) root sliding down an incline).
    Free,
}

impl Default for StepOptions {
    fn default() -> Self {
        Self {
            time_step: 0.01,
            head_correction: 0.5,
            push_out: 1.0,
            limit_margin: 2f64.to_radians(),
            self_contact: true,
            contact: DetectorOptions { margin: 0.1, ..DetectorOptions::default() },
            contact_exclusion_diameters: 2.0,
            wall: Some((DVec3::ZERO, DVec3::X)),
            wall_options: WallOptions { margin: 0.2, ..WallOptions::default() },
            solver: SolverOptions::default(),
            velocity_product_iterations: 1,
            backend: DynamicsBackend::default(),
            contact_prediction: Some(0.001),
            acceptance: StepAcceptance::default(),
            friction: None,
            obstacles: Vec::new(),
            obstacle_groove: Some(DEFAULT_GROOVE_FRACTION),
            root: RootHold::Held,
        }
    }
}

impl StepOptions {
    /// The self-contact detector options for `model`: [`StepOptions::contact`] with the
    /// chain-index gap and cluster radius of the body-relative rule of
    /// [`StepOptions::contact_exclusion_diameters`].
    pub fn detector_options(&self, model: &Model) -> DetectorOptions {
        let widest = model.bodies().iter().map(|b| 2.0 * b.radius).fold(0.0, f64::max);
        let shortest = model.bodies().iter().map(|b| b.length).fold(f64::INFINITY, f64::min);
        let gap = (self.contact_exclusion_diameters * widest / shortest).round();
        let index_gap = if gap.is_finite() { (gap as usize).max(2) } else { 2 };
        DetectorOptions { index_gap, cluster_radius: 0.1875 * index_gap as f64, ..self.contact }
    }

    /// The cluster radius (in bodies) of a step retried with contacts at the chain's
    /// resolution: [`RESOLVED_CLUSTER_BODIES`], scaled by N/[`FINEST_RESOLVED_CHAIN`] on
    /// chains of more bodies, or the body-relative radius of
    /// [`StepOptions::detector_options`] where that is not larger (ES103 and chains of up to
    /// 101 bodies at its proportions, on which the retry changes nothing).
    pub fn resolved_cluster_radius(&self, model: &Model) -> f64 {
        let finer = model.body_count() as f64 / FINEST_RESOLVED_CHAIN as f64;
        let resolved = RESOLVED_CLUSTER_BODIES * finer.max(1.0);
        self.detector_options(model).cluster_radius.min(resolved)
    }

    /// Checks every scalar option.
    pub fn validate(&self) -> Result<(), SimError> {
        let check = |name, value: f64, ok: bool, expected| {
            if ok && value.is_finite() {
                Ok(())
            } else {
                Err(SimError::InvalidOption { name, value, expected })
            }
        };
        check("time_step", self.time_step, self.time_step > 0.0, "finite and > 0 (s)")?;
        let fraction = "in (0, 1]";
        check(
            "head_correction",
            self.head_correction,
            self.head_correction > 0.0 && self.head_correction <= 1.0,
            fraction,
        )?;
        check("push_out", self.push_out, self.push_out > 0.0 && self.push_out <= 1.0, fraction)?;
        check("limit_margin", self.limit_margin, self.limit_margin >= 0.0, "finite and ≥ 0 (rad)")?;
        check(
            "contact_exclusion_diameters",
            self.contact_exclusion_diameters,
            self.contact_exclusion_diameters > 0.0,
            "finite and > 0",
        )?;
        self.acceptance.validate()?;
        if let Some(friction) = &self.friction {
            friction.validate()?;
            if friction.cone == ConeForm::Exact && self.solver.backend != QpBackend::Clarabel {
                return Err(SimError::ExactConeNeedsClarabel);
            }
        }
        match self.contact_prediction {
            Some(tolerance) => {
                check("contact_prediction", tolerance, tolerance >= 0.0, "finite and ≥ 0 (cm)")
            }
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use hagfish_anatomy::Body;

    use super::*;

    /// ES103 (`data/hagfish/es103.ron`) made of `bodies` bodies.
    fn es103(bodies: usize) -> Model {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/hagfish/es103.ron");
        let Body::Hagfish(mut biometrics) = Body::load(path).expect("es103.ron") else {
            panic!("es103.ron is a hagfish")
        };
        biometrics.body_count = bodies;
        biometrics.to_model().expect("a model")
    }

    #[test]
    fn retries_resolve_at_one_and_a_half_bodies_up_to_300_and_the_same_length_beyond() {
        let options = StepOptions::default();
        let radii = |bodies| {
            let model = es103(bodies);
            (
                options.detector_options(&model).cluster_radius,
                options.resolved_cluster_radius(&model),
            )
        };
        // ES103 itself: the body-relative radius is already 1.5 bodies, so no retry differs.
        assert_eq!(radii(100), (1.5, 1.5));
        assert_eq!(radii(300), (4.6875, 1.5));
        // Finer: 1.5 bodies of the 300-body chain, not a tenth of the body-relative radius.
        let (coarse, resolved) = radii(1000);
        assert!(coarse > 15.0, "{coarse}");
        assert_eq!(resolved, 5.0);
    }

    #[test]
    fn the_exact_cone_is_refused_without_the_reference_backend() {
        let exact = StepOptions { friction: Some(Friction::exact(0.2)), ..StepOptions::default() };
        assert!(matches!(exact.validate(), Err(SimError::ExactConeNeedsClarabel)));
        let solver = SolverOptions { backend: QpBackend::Clarabel, ..SolverOptions::default() };
        assert!(StepOptions { solver, ..exact }.validate().is_ok());
    }
}
