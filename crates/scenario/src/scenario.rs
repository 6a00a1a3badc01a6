//! Scenario files (RON): which body, the time step and duration, drag, the phases of control,
//! and what to record. Paths inside a scenario are relative to the scenario file.
//!
//! ```ron
//! Scenario(
//!     name: "form",
//!     body: "../hagfish/es103.ron",
//!     time_step_s: 0.01,
//!     duration_s: 20.0,
//!     record_every_s: 0.1,
//!     drag: Some((linear_dyn_s_per_cm3: 0.0, quadratic_g_per_cm3: 0.5)),
//!     phases: [Form((gains: (...), steps: [...]))],
//! )
//! ```

use std::path::{Path, PathBuf};

use hagfish_anatomy::{AnatomyError, Body, BodySkin, DataFile, Field, read_data_file};
use hagfish_control::{Phase, PhasedController, WaterDrag, diameters_tail_ward};
use hagfish_geometry::MovingObstacle;
use hagfish_tree::{Model, State};
use serde::{Deserialize, Serialize};

use hagfish_sim::rows::{ConeForm, Friction};
use hagfish_solver::QpBackend;

use crate::obstacles::ObstacleSpec;
use hagfish_sim::{DynamicsBackend, StepAcceptance, StepOptions, World, fnv1a64};

use crate::error::ScenarioError;
use crate::initial_shape::InitialShape;
use crate::knot_plan_file::resolve_knot_plans;
use crate::knot_template_file::resolve_knot_templates;
use crate::modal_space::resolve_modal_spaces;
use crate::overrides::{Override, apply_overrides};
use crate::polyline_shape::resolve_polyline;
use crate::referenced_files::{referenced_files, referenced_files_hash};
use crate::replay_file::resolve_replays;
use crate::scenario_check::check_scenario;

/// The content of a scenario file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// A short name, used in outputs.
    pub name: String,
    /// The body file (hagfish biometrics or a rod), relative to the scenario file (absolute
    /// once loaded).
    pub body: PathBuf,
    /// Time step h (s), at least [`MIN_TIME_STEP_S`].
    pub time_step_s: f64,
    /// Simulated time (s), > 0.
    pub duration_s: f64,
    /// End the run as soon as the last phase is over (e.g. a load phase has settled), with a
    /// frame recorded there, instead of at `duration_s` (default false).
    #[serde(default)]
    pub end_after_phases: bool,
    /// Interval between recorded frames (s), rounded to a whole number of time steps (at
    /// least one); frame 0 is the initial state.
    #[serde(default = "default_record_every")]
    pub record_every_s: f64,
    /// Interval (s) at which the controller observes the knot, rounded as `record_every_s`:
    /// the knot analysis that ends a `Tie` phase and the knotted core that the `core_*` end
    /// conditions read. Part of the control, apart from `record_every_s`, so that recording
    /// more or fewer frames does not change the run (default 0.1 s).
    #[serde(default = "default_observe_every")]
    pub observe_every_s: f64,
    /// Water drag on the body, or `None` for a body in vacuum.
    #[serde(default)]
    pub drag: Option<WaterDrag>,
    /// The body's shape at t = 0 ([`InitialShape`]), or `None` (default): straight along +X.
    #[serde(default)]
    pub initial_shape: Option<InitialShape>,
    /// A skin for the body (docs/physics.md, "Skin") in place of the body file's, for studies
    /// that give one body file a skin (`--set skin=Some((thickness_fraction: 0.25,
    /// pressure_dyn_per_cm2: 300.0))`); `None` (default): the body file's own. A hagfish body
    /// only.
    #[serde(default)]
    pub skin: Option<BodySkin>,
    /// The phases of control, in order.
    pub phases: Vec<Phase>,
    /// The linear algebra of the velocity step: `SparseMaximal` (default; linear in the number
    /// of bodies) or `DenseReduced` (cubic; the reference). Same answer up to rounding.
    #[serde(default)]
    pub backend: DynamicsBackend,
    /// When a step's result is accepted, and how far a rejected step is divided
    /// ([`StepAcceptance`]; defaults suit any body).
    #[serde(default)]
    pub acceptance: StepAcceptance,
    /// Coulomb friction on the self contacts and the wall (docs/physics.md, "Friction: the
    /// cone and its pyramid"): `Some((coefficient: 0.1))`, optionally `edges: E` (default 8)
    /// and `cone: Exact` (the exact cone, run on the clarabel backend); `None` (default):
    /// frictionless, as the thesis.
    #[serde(default)]
    pub friction: Option<Friction>,
    /// Rigid obstacles, still or moving on a path (`Moving(shape: …, path: […])`), that the
    /// body touches as it touches the wall (docs/physics.md, "Obstacles"; default none).
    #[serde(default)]
    pub obstacles: Vec<ObstacleSpec>,
    /// How finely the obstacles see the body's tube (docs/physics.md, "Obstacles"): the
    /// deepest groove an obstacle's edge may reach unseen between two of the points they
    /// touch, as a fraction of the local radius, `Some(0.05)` (default) or any in (0, 1];
    /// `None`: the bodies' spheres alone, a chain of beads.
    #[serde(default = "default_obstacle_groove")]
    pub obstacle_groove: Option<f64>,
    /// The self contacts' speculative margin (cm, > 0; default 0.1): a pair of strands closer
    /// than it is a contact row, so that a step that would close the gap stops at touching
    /// (docs/physics.md, "Contact detection"). It must cover how far two strands approach in
    /// one step; a wider one only adds rows that stay slack. Thin rods in tight knots have many
    /// neighbours within 0.1 cm, each a row and in the pyramid three solved columns.
    #[serde(default = "default_contact_margin")]
    pub contact_margin_cm: f64,
}

fn default_obstacle_groove() -> Option<f64> {
    Some(hagfish_geometry::DEFAULT_GROOVE_FRACTION)
}

fn default_contact_margin() -> f64 {
    StepOptions::default().contact.margin
}

/// The smallest time step a scenario may ask for (s): below it a run cannot make progress in
/// any reasonable time (30 s of simulation would be 3·10⁷ steps, ≈ 1.5 h at 100 bodies).
pub const MIN_TIME_STEP_S: f64 = 1e-6;

fn default_record_every() -> f64 {
    0.1
}

fn default_observe_every() -> f64 {
    0.1
}

/// `scenario` as pretty RON text with struct names, the format of a run's `scenario.ron`.
fn pretty_ron(scenario: &Scenario) -> String {
    let config = ron::ser::PrettyConfig::default().struct_names(true);
    // Serializing plain data (strings, numbers, enums, sequences) into a string cannot fail.
    ron::ser::to_string_pretty(scenario, config).unwrap_or_default()
}

/// A scenario with its body (hagfish biometrics or rod) loaded and checked.
#[derive(Clone, Debug)]
pub struct LoadedScenario {
    /// The scenario as read, with the body path and the modal spaces' files made absolute and
    /// each modal space's basis resolved on the body (`modal_space.rs`; not serialised).
    pub scenario: Scenario,
    /// The body file's content.
    pub body: Body,
    /// The scenario file's path.
    pub path: PathBuf,
    /// FNV-1a hash of the body file's bytes (16 hex digits), so that a resume can tell that
    /// the body file changed although the scenario (which names it) did not.
    pub body_hash: String,
    /// FNV-1a hash of the knot plans, modal bases and replays the phases read (16 hex
    /// digits; empty when they read none), for the same reason (`referenced_files.rs`).
    pub referenced_files_hash: String,
}

impl LoadedScenario {
    /// Reads the scenario at `path`, checks its values (each error at its `file:line:column`)
    /// and loads the body file it names.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, ScenarioError> {
        Self::checked(DataFile::<Scenario>::read(path.as_ref())?)
    }

    /// Reads the scenario at `path` as [`load`](Self::load) does, with `overrides` applied
    /// (`overrides.rs`) before its values are checked. A check that fails on the overridden
    /// scenario is reported with the overrides and a location in the overridden text (as
    /// [`resolved_text`](Self::resolved_text) writes it, body path aside).
    pub fn load_with(
        path: impl AsRef<Path>,
        overrides: &[Override],
    ) -> Result<Self, ScenarioError> {
        let path = path.as_ref();
        if overrides.is_empty() {
            return Self::load(path);
        }
        let file = DataFile::<Scenario>::read(path)?;
        let scenario = apply_overrides(&file.value, overrides)?;
        let text = pretty_ron(&scenario);
        let label = PathBuf::from(format!("{} [with overrides]", path.display()));
        let mut loaded =
            Self::parse(text.as_bytes(), &label).map_err(|source| ScenarioError::Overridden {
                overrides: overrides.iter().map(Override::text).collect::<Vec<_>>().join(" "),
                source: Box::new(source),
            })?;
        loaded.path = path.to_path_buf();
        Ok(loaded)
    }

    /// Parses scenario `bytes` as if read from `path` (which names the source in messages and
    /// locates the body file), then checks it as [`load`](Self::load) does.
    pub fn parse(bytes: &[u8], path: &Path) -> Result<Self, ScenarioError> {
        Self::checked(DataFile::<Scenario>::parse(bytes, path)?)
    }

    fn checked(file: DataFile<Scenario>) -> Result<Self, ScenarioError> {
        let directory = file.path.parent().unwrap_or(Path::new("."));
        let body = directory.join(&file.value.body);
        let mut loaded = Body::load(&body).map_err(|source| match source {
            AnatomyError::Io { .. } => ScenarioError::BodyFile {
                at: file.locate(&Field::whole("body")),
                source: Box::new(source),
            },
            other => ScenarioError::DataFile(other),
        })?;
        let model = loaded.to_model()?;
        let diameters = diameters_tail_ward(model.bodies(), 0.0);
        check_scenario(&file, loaded.body_count(), loaded.length_cm(), diameters)?;
        if let Some(skin) = file.value.skin {
            let Body::Hagfish(biometrics) = &mut loaded else {
                return Err(ScenarioError::SkinOnRod { at: file.locate(&Field::whole("skin")) });
            };
            biometrics.skin = Some(skin);
        }
        let phases = resolve_modal_spaces(&file, directory, &model, loaded.length_cm())?;
        let phases = resolve_replays(&file, directory, phases, model.dof_count())?;
        let phases = resolve_knot_plans(&file, directory, phases)?;
        let phases = resolve_knot_templates(&file, directory, &model, phases)?;
        let bytes = read_data_file(&body).map_err(|source| ScenarioError::BodyFile {
            at: file.locate(&Field::whole("body")),
            source: Box::new(source),
        })?;
        let body_hash = format!("{:016x}", fnv1a64(&bytes));
        let initial_shape = match file.value.initial_shape.clone() {
            Some(InitialShape::Polyline(shape)) => {
                Some(InitialShape::Polyline(resolve_polyline(&file, directory, shape)?))
            }
            other => other,
        };
        let body = std::fs::canonicalize(&body).unwrap_or(body);
        let resolved = Scenario { body, phases, initial_shape, ..file.value };
        let referenced_files_hash = referenced_files_hash(&referenced_files(&resolved))?;
        Ok(Self {
            scenario: resolved,
            body: loaded,
            path: file.path,
            body_hash,
            referenced_files_hash,
        })
    }

    /// The scenario as RON text with every default filled in and the body file as an absolute
    /// path: the `scenario.ron` of a run directory, loadable from anywhere.
    pub fn resolved_text(&self) -> String {
        pretty_ron(&self.scenario)
    }

    /// FNV-1a hash of [`resolved_text`](Self::resolved_text), as 16 hex digits.
    pub fn hash(&self) -> String {
        format!("{:016x}", fnv1a64(self.resolved_text().as_bytes()))
    }

    /// The scenario's phases placed on `model`, the model of its body: each tie's crossover
    /// moved head-ward where its `min_tail_d` asks for more tube ([`Phase::on_body`]).
    fn phases_on(&self, model: &Model) -> Vec<Phase> {
        self.scenario.phases.iter().map(|p| p.on_body(model.bodies())).collect()
    }

    /// Where each tie phase makes its crossover on this body, in phase order (fraction of the
    /// body length from the head): its `at`, or head-ward of it by its `min_tail_d`.
    pub fn tie_crossovers_l(&self) -> Result<Vec<f64>, ScenarioError> {
        let phases = self.phases_on(&self.body.to_model()?);
        Ok(phases
            .iter()
            .filter_map(|p| if let Phase::Tie(tie) = p { Some(tie.at) } else { None })
            .collect())
    }

    /// The world at rest and the scenario's controller, ready to run.
    pub fn build(&self) -> Result<(World, PhasedController), ScenarioError> {
        let model = self.body.to_model()?;
        let mut state = State::rest(&model);
        if let Some(shape) = &self.scenario.initial_shape {
            state.q = shape.pose(&model, self.body.length_cm());
        }
        let obstacles = (self.scenario.obstacles.iter().enumerate())
            .map(|(index, spec)| {
                spec.to_obstacle().map_err(|source| ScenarioError::Obstacle { index, source })
            })
            .collect::<Result<Vec<_>, _>>()?;
        refuse_obstacles_on_the_head(&model, &state, &obstacles)?;
        let mut options = StepOptions {
            time_step: self.scenario.time_step_s,
            obstacles,
            backend: self.scenario.backend,
            acceptance: self.scenario.acceptance,
            friction: self.scenario.friction,
            obstacle_groove: self.scenario.obstacle_groove,
            ..StepOptions::default()
        };
        options.contact.margin = self.scenario.contact_margin_cm;
        // The exact friction cone is solved by the reference backend only.
        if self.scenario.friction.is_some_and(|f| f.cone == ConeForm::Exact) {
            options.solver.backend = QpBackend::Clarabel;
        }
        let phases = self.phases_on(&model);
        let world = World::new(model, options, state)?;
        let controller = PhasedController::new(self.scenario.drag, phases);
        Ok((world, controller))
    }

    /// The world and controller after running the scenario from rest to time `time_s`
    /// (rounded to whole steps; no recording): e.g. the knotted state of the benchmarks.
    pub fn build_at(&self, time_s: f64) -> Result<(World, PhasedController), ScenarioError> {
        let (mut world, mut controller) = self.build()?;
        let steps = (time_s / self.scenario.time_step_s).round() as u64;
        for _ in 0..steps {
            world.step(&mut controller)?;
        }
        Ok((world, controller))
    }
}

/// [`ScenarioError::ObstacleOverlapsHead`] if an obstacle at t = 0 overlaps the head body's
/// sphere (its centre, its radius) posed by `state`.
fn refuse_obstacles_on_the_head(
    model: &Model,
    state: &State,
    obstacles: &[MovingObstacle],
) -> Result<(), ScenarioError> {
    let Some(head) = model.bodies().first() else { return Ok(()) };
    let mut data = hagfish_tree::Data::new(model);
    hagfish_tree::position_kinematics(model, &state.q, &mut data);
    let centre = data.body_centre(0);
    for (index, obstacle) in obstacles.iter().enumerate() {
        let (distance, _) = obstacle.at(0.0).distance(centre);
        let depth_cm = head.radius - distance;
        if depth_cm > 0.0 {
            return Err(ScenarioError::ObstacleOverlapsHead { index, depth_cm });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `tests/data/form.ron` with `backend` set, parsed as if it sat in `tests/data/`.
    fn short_form_with(backend: &str) -> LoadedScenario {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
        let path = Path::new(root).join("tests/data/form.ron");
        let text = std::fs::read_to_string(&path).expect("tests/data/form.ron");
        let text = text.replace("phases: [", &format!("{backend}phases: ["));
        LoadedScenario::parse(text.as_bytes(), &path).expect("parses")
    }

    #[test]
    fn an_obstacle_on_the_held_head_is_refused_and_one_beside_it_is_not() {
        let on = short_form_with("obstacles: [Sphere(centre: (0.5, 0.0, 0.0), radius: 1.0)], ");
        let Err(error) = on.build() else { panic!("built with the head inside a sphere") };
        assert!(
            matches!(error, ScenarioError::ObstacleOverlapsHead { index: 0, depth_cm } if depth_cm > 0.0),
            "{error}"
        );
        assert!(error.to_string().contains("obstacles[0] overlaps the head"), "{error}");
        let beside = short_form_with("obstacles: [Sphere(centre: (0.5, 5.0, 0.0), radius: 1.0)], ");
        assert!(beside.build().is_ok());
    }

    #[test]
    fn the_backend_of_a_scenario_reaches_the_step_options() {
        let (world, _) = short_form_with("backend: DenseReduced, ").build().expect("builds");
        assert_eq!(world.options().backend, DynamicsBackend::DenseReduced);
        let (world, _) = short_form_with("").build().expect("builds");
        assert_eq!(world.options().backend, DynamicsBackend::SparseMaximal);
    }
}
