//! Everything a step derives or needs as scratch, allocated once per world.

use faer::Mat;
use glam::DVec3;
use hagfish_control::Actuation;
use hagfish_geometry::{
    Centreline, ContactDetector, DetectionReport, PAIRS_PER_BODY, SelfContact, TubeSamples, Wall,
    WallContact, WallOptions,
};
use hagfish_solver::{Rows, SolverError, SolverWorkspace};
use hagfish_sparse::TreeFactor;
use hagfish_tree::{Data, Model, State, position_kinematics};

use crate::backend::DynamicsBackend;
use crate::carried_contacts::{Carried, CarriedContacts};
use crate::contact_prediction::ContactPredictor;
use crate::error::SimError;
use crate::internal_forces::InternalForces;
use crate::memory::check_memory;
use crate::options::StepOptions;
use crate::report::StepReport;
use crate::rows::{RowGroup, twist_dofs};
use crate::skin::{SkinLayer, SkinRecords};
use crate::warm_start::WarmStart;

/// Rows (and solver buffers) reserved per DOF on the dense backend: 2n rows cover the head,
/// every limit and more than twice the self contacts of the tightest knots measured (≈ 45), so
/// knotted steps do not allocate; a step with more rows still works and grows the buffers.
const ROWS_PER_DOF: usize = 2;

/// Rows reserved on the sparse backend, whose memory must stay linear in the bodies: the rows
/// and the contact-space matrices (n × m and m × m) are sized by the rows present, growing
/// (doubling) during the first steps that need more.
const SPARSE_ROW_RESERVE: usize = 128;

/// The rows to reserve for `model` on `backend`.
pub(crate) fn row_reserve(model: &Model, backend: DynamicsBackend) -> usize {
    match backend {
        DynamicsBackend::DenseReduced => ROWS_PER_DOF * model.dof_count(),
        DynamicsBackend::SparseMaximal => SPARSE_ROW_RESERVE.min(ROWS_PER_DOF * model.dof_count()),
    }
}

/// An empty vector with room for `capacity` values, or the error naming `what`.
fn try_vec<T>(capacity: usize, what: &str) -> Result<Vec<T>, SolverError> {
    let mut buffer = Vec::new();
    buffer.try_reserve_exact(capacity).map_err(|_| SolverError::Allocation {
        what: format!("{what} ({capacity} × {} bytes)", size_of::<T>()),
        bytes: (capacity as u64).saturating_mul(size_of::<T>() as u64),
    })?;
    Ok(buffer)
}

/// The per-step data of a [`crate::World`]: tree quantities, contact geometry, rows, solver
/// workspace and the last report. Each field names the stage that fills it.
#[derive(Debug)]
pub struct StepData {
    /// Kinematics, mass matrix, forces, M̃ and f̃ (stages `kinematics`, `dynamics`).
    pub tree: Data,
    /// The centreline through the body centres (stage `detect_contacts`).
    pub centreline: Centreline,
    /// Self contacts, sorted head to tail by the anterior parameter (stage `detect_contacts`).
    pub self_contacts: Vec<SelfContact>,
    /// Bodies touching the wall, and points of the tube touching an obstacle (stage
    /// `detect_contacts`).
    pub wall_contacts: Vec<WallContact>,
    /// The points of the tube that obstacles touch (fixed for the model and options).
    pub tube_samples: TubeSamples,
    /// What the controller asked for this step (stage `control`).
    pub actuation: Actuation,
    /// Constraint rows of this step (stage `build_rows`).
    pub rows: Rows,
    /// The velocity solve: q̇¹, multipliers, per-group impulses (stage `solve_velocities`).
    pub solver: SolverWorkspace,
    /// The report of the last step.
    pub report: StepReport,
    /// The sparse backend's factor of the maximal-coordinate system (stages `dynamics` and
    /// `solve_velocities`); `None` on the dense backend.
    pub tree_factor: Option<TreeFactor>,
    /// The load each joint transmits during the step (stage `internal_forces`).
    pub internal: InternalForces,
    /// Whether stage `internal_forces` runs in the next steps ([`crate::World::set_internal_forces_due`]).
    pub(crate) internal_forces_due: bool,
    pub(crate) detector: ContactDetector,
    pub(crate) wall: Option<Wall>,
    pub(crate) centres: Vec<DVec3>,
    pub(crate) radii: Vec<f64>,
    pub(crate) lengths: Vec<f64>,
    /// The indices of the twist DOFs, which a `BendingOnly` thigmotaxis row leaves out.
    pub(crate) twist_dofs: Vec<usize>,
    /// One value per DOF, allocated here once: a modal force space's `Bᵀc` (k ≤ n values).
    pub(crate) modal_scratch: Vec<f64>,
    pub(crate) velocity_guess: Vec<f64>,
    /// The dense `M̃` while stage 6 solves with it (`solve_and_resolve` swaps it out of `tree`
    /// and back); an empty matrix otherwise.
    pub(crate) effective_mass: Mat<f64>,
    /// The right-hand sides of stage 6's solves: the rows' own, raised where the contact
    /// prediction asks for more.
    pub(crate) bounds: Vec<f64>,
    pub(crate) predictor: ContactPredictor,
    /// The bodies' skins (docs/physics.md, "Skin").
    pub skin: SkinLayer,
    /// Which self contacts carry a skin spring (stage `build_rows`).
    pub(crate) skin_records: SkinRecords,
    /// The contacts of the state the last step ended in, for the next step to take over.
    pub(crate) carried: CarriedContacts,
    /// The last solve's multipliers by what their rows constrain: the next step's start.
    pub warm_start: WarmStart,
}

/// The wall of `options`, testing only the bodies from the first one whose sphere clears the
/// wall by its margin in the rest shape (`centres`) on, and never fewer than
/// `options.wall_options.first_body`: the bodies that touch the wall by construction depend on
/// the radii and the segment length, not on a fixed count.
fn wall_for(
    point: DVec3,
    normal: DVec3,
    options: &StepOptions,
    centres: &[DVec3],
    radii: &[f64],
) -> Result<Wall, hagfish_geometry::GeometryError> {
    let given = Wall::new(point, normal, options.wall_options)?;
    let first_body = given.first_clear_body(centres, radii).max(options.wall_options.first_body);
    Wall::new(point, normal, WallOptions { first_body, ..options.wall_options })
}

impl StepData {
    /// Allocates everything for `model` and `options`, after checking that it fits in the
    /// available memory ([`check_memory`]).
    pub fn new(model: &Model, options: &StepOptions) -> Result<Self, SimError> {
        check_memory(model, options.backend)?;
        let geometry = |source| SimError::Geometry { step: 0, time: 0.0, source };
        let radii: Vec<f64> = model.bodies().iter().map(|b| b.radius).collect();
        let lengths: Vec<f64> = model.bodies().iter().map(|b| b.length).collect();
        let mut tree = Data::new(model);
        // The rest shape (q = 0): what the wall's exclusion of the head's bodies is measured on.
        position_kinematics(model, &State::rest(model).q, &mut tree);
        let centres: Vec<DVec3> = (0..model.body_count()).map(|i| tree.body_centre(i)).collect();
        let centreline = Centreline::new(&centres, &radii).map_err(geometry)?;
        let tube_samples =
            TubeSamples::new(&lengths, &radii, options.obstacle_groove).map_err(geometry)?;
        let mut detector =
            ContactDetector::new(options.detector_options(model)).map_err(geometry)?;
        detector.reserve(model.body_count());
        let wall = options
            .wall
            .map(|(point, normal)| wall_for(point, normal, options, &centres, &radii))
            .transpose()
            .map_err(geometry)?;
        // The largest buffers (the rows, the contact-space matrices, the contact lists) are
        // allocated fallibly: a limit the estimate missed is an error, not an abort.
        let bodies = model.body_count();
        let allocation = |source| SimError::Allocation { bodies, source };
        let mut solver = SolverWorkspace::new(options.solver);
        let reserve = row_reserve(model, options.backend);
        solver.try_reserve(model.dof_count(), reserve).map_err(allocation)?;
        let rows = Rows::try_with_capacity(model.dof_count(), reserve).map_err(allocation)?;
        let skin = SkinLayer::new(model);
        let skin_radius = options.detector_options(model).cluster_radius;
        let skin_records = SkinRecords::new(
            skin_radius,
            if skin.is_present() { PAIRS_PER_BODY * bodies } else { 0 },
        );
        let predictor = ContactPredictor::new(model, &centreline, &skin);
        let pairs = PAIRS_PER_BODY * bodies;
        let contacts = || try_vec(pairs, "the self contacts").map_err(allocation);
        let carried = CarriedContacts {
            centres: centres.clone(),
            centreline: centreline.clone(),
            self_contacts: contacts()?,
            wall_contacts: Vec::new(),
            detection: DetectionReport::default(),
            status: Carried::Stale,
        };
        Ok(Self {
            tree,
            centreline,
            self_contacts: contacts()?,
            wall_contacts: Vec::new(),
            tube_samples,
            actuation: Actuation::default(),
            rows,
            solver,
            report: StepReport::default(),
            tree_factor: match options.backend {
                DynamicsBackend::DenseReduced => None,
                DynamicsBackend::SparseMaximal => Some(TreeFactor::new(model)?),
            },
            internal: InternalForces::new(model.body_count()),
            internal_forces_due: true,
            detector,
            wall,
            centres,
            radii,
            lengths,
            twist_dofs: twist_dofs(model),
            modal_scratch: vec![0.0; model.dof_count()],
            velocity_guess: vec![0.0; model.dof_count()],
            effective_mass: Mat::zeros(0, 0),
            bounds: try_vec(reserve, "the rows' bounds").map_err(allocation)?,
            predictor,
            skin,
            skin_records,
            carried,
            warm_start: WarmStart::default(),
        })
    }

    /// The generalized force of a row group over the last step, `C_gᵀλ_g / h` (dyn·cm per
    /// rotational DOF), written into `out` (length n).
    pub fn group_force(&self, group: RowGroup, time_step: f64, out: &mut [f64]) {
        for (f, impulse) in out.iter_mut().zip(self.solver.tag_impulse(group.tag())) {
            *f = impulse / time_step;
        }
    }
}
