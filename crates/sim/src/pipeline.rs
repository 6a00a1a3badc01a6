//! The step, as a sequence of named stages (`docs/architecture.md`):
//!
//! ```text
//! kinematics → detect_contacts → control → dynamics → build_rows
//!   → solve_and_resolve: solve → [predict contact gaps | refresh velocity products
//!      | add overshooting limit rows → solve]* → internal_forces → integrate → check_result
//! ```
//!
//! `check_result` runs the kinematics and contact detection of the new state, judges it
//! ([`crate::StepAcceptance`]) and keeps what it detected for the next step, whose first two
//! stages then take it over instead of running again: one detection per step.
//!
//! Each stage is a public function of the immutable model and options and the mutable step
//! data, so tests and benchmarks can run any prefix.

use hagfish_control::{ControlContext, Controller, tail_end};
use hagfish_solver::SolveStatus;
use hagfish_tree::{Model, State};

use hagfish_geometry::DetectionReport;

use crate::acceptance::EndOfStep;
use crate::backend;
use crate::carried_contacts::Carried;
use crate::error::{InStep, SimError, StepAt};
pub use crate::internal_forces::internal_forces;
use crate::options::{RootHold, StepOptions};
use crate::report::{Stage, StageClock, StepReport};
use crate::rows::{
    add_grip_rows, add_head_rows, add_limit_rows, add_overshooting_limit_rows,
    add_self_contact_rows, add_thigmo_rows, add_wall_rows, overshoots_limit,
};
use crate::step_data::StepData;
use crate::stop::StopRequest;

/// Cap on the extra solves of one step (velocity-product refreshes and limit rows added for
/// overshooting joints).
const MAX_RESOLVES: usize = 4;

/// Stage 1: frames, axes, twists and velocity products for `state`.
pub fn kinematics(model: &Model, state: &State, data: &mut StepData) {
    hagfish_tree::forward_kinematics(model, &state.q, &state.qdot, &mut data.tree);
}

/// Stage 2: centreline through the body centres, self contacts and wall and obstacle contacts
/// (the obstacles where their paths have them at `time`, s); returns the self-contact
/// detection's counts.
pub fn detect_contacts(
    model: &Model,
    options: &StepOptions,
    time: f64,
    data: &mut StepData,
) -> Result<DetectionReport, hagfish_geometry::GeometryError> {
    for (i, centre) in data.centres.iter_mut().enumerate() {
        *centre = data.tree.body_centre(i);
    }
    debug_assert_eq!(data.centres.len(), model.body_count());
    data.centreline.update(&data.centres, &data.radii)?;
    data.self_contacts.clear();
    let detection = if options.self_contact {
        data.detector.detect(&data.centreline, &data.lengths, &mut data.self_contacts)?
    } else {
        DetectionReport::default()
    };
    data.wall_contacts.clear();
    if let Some(wall) = &data.wall {
        wall.contacts(&data.centreline, &mut data.wall_contacts);
    }
    let margin = options.wall_options.margin;
    for obstacle in &options.obstacles {
        let tube = (&data.centreline, &data.tube_samples);
        obstacle.contacts(tube, margin, time, &mut data.wall_contacts);
    }
    Ok(detection)
}

/// Stage 3: the controller sees the state, kinematics and contacts and sets this step's
/// forces and implicit dampers.
pub fn control(
    model: &Model,
    options: &StepOptions,
    state: &State,
    data: &mut StepData,
    controller: &mut dyn Controller,
) {
    data.actuation.clear();
    let context = ControlContext {
        model,
        state,
        kinematics: &data.tree,
        centreline: &data.centreline,
        self_contacts: &data.self_contacts,
        time_step: options.time_step,
    };
    controller.control(&context, &mut data.actuation);
    data.tree.clear_applied();
    data.actuation.apply_to(&mut data.tree);
}

/// Stage 4: `M̃ = M + h Jᵀ C_m J + hD + h²K` (with the implicit dampers of stage 3; dense, or
/// its maximal-coordinate blocks on the sparse backend), the momentum `M q̇⁰`, the generalized
/// force and `f̃ = M q̇⁰ + h f_r`.
pub fn dynamics(model: &Model, options: &StepOptions, state: &State, data: &mut StepData) {
    let h = options.time_step;
    backend::assemble_effective_mass(model, data, h);
    hagfish_tree::generalized_momentum(model, &mut data.tree);
    hagfish_tree::generalized_force(model, &state.q, &mut data.tree);
    hagfish_tree::assemble_effective_momentum(&mut data.tree, h);
}

/// Stage 5: the rows of this step: head (unless the root is free), joint limits, wall, self
/// contact, thigmotaxis, grip; and the start of their multipliers, the last step's by what
/// each row constrains (`warm_start.rs`).
pub fn build_rows(model: &Model, options: &StepOptions, state: &State, data: &mut StepData) {
    let h = options.time_step;
    data.rows.clear();
    if options.root == RootHold::Held {
        add_head_rows(model, state, h, options.head_correction, &mut data.rows);
    }
    add_limit_rows(model, state, h, options.limit_margin, options.push_out, &mut data.rows);
    let stabilisation = (h, options.push_out, options.friction);
    add_wall_rows(model, &data.tree, &data.wall_contacts, stabilisation, &mut data.rows);
    let skin_carriers = if data.skin.is_present() {
        let detected_radius = data.detector.options().cluster_radius;
        data.skin_records.carriers(&data.self_contacts, detected_radius)
    } else {
        None
    };
    add_self_contact_rows(
        model,
        &data.tree,
        &data.self_contacts,
        &data.centreline,
        (&data.skin, skin_carriers),
        stabilisation,
        &mut data.rows,
    );
    add_thigmo_rows(
        model,
        &data.tree,
        &data.self_contacts,
        &data.actuation.thigmo,
        &data.twist_dofs,
        &mut data.modal_scratch,
        h,
        &mut data.rows,
    );
    if let Some(grip) = &data.actuation.grip {
        let correction = (h, options.head_correction);
        add_grip_rows(model, &data.tree, grip, correction, &mut data.rows);
    }
    let contacts = (&data.self_contacts[..], &data.wall_contacts[..]);
    data.warm_start.hand_to(&data.rows, contacts, &mut data.solver);
}

/// Stage 6, one solve: `min ½q̇ᵀM̃q̇ − q̇ᵀf̃` subject to the rows; the path (Cholesky, KKT, QP)
/// follows from the rows present; `M̃` is the options' backend's. The step runs it with its
/// re-solves ([`solve_and_resolve`]).
pub fn solve_velocities(data: &mut StepData) -> Result<(), hagfish_solver::SolverError> {
    let StepData { tree, tree_factor, rows, solver, report, .. } = data;
    let mass = backend::mass(&tree.effective_mass, tree_factor)?;
    report.solve = *solver.factor(mass, rows)?.solve(&tree.effective_momentum, rows.rhs())?;
    Ok(())
}

/// Part of stage 6: re-evaluates the velocity-product (Coriolis, centrifugal, gyroscopic)
/// force at the velocity `solved` just solved for and re-forms `f̃ = M q̇⁰ + h f_r` in `tree`
/// (the momentum `M q̇⁰` and `M̃` are kept), so that the next solve treats it implicitly (a
/// fixed-point iteration). Applied forces are kept; positions are unchanged, so the rows stay
/// valid, and so are the frames and axes of stage 1: only the twists and velocity-product
/// accelerations are formed again (at `guess`, a copy of `solved`).
fn refresh_velocity_products(
    model: &Model,
    options: &StepOptions,
    state: &State,
    solved: &[f64],
    guess: &mut [f64],
    tree: &mut hagfish_tree::Data,
) {
    guess.copy_from_slice(solved);
    hagfish_tree::velocity_kinematics(model, guess, tree);
    hagfish_tree::generalized_force(model, &state.q, tree);
    hagfish_tree::assemble_effective_momentum(tree, options.time_step);
}

/// Runs one whole step and advances `state` (see the module docs for the stages). On error the
/// state is left as it was; `stop` is polled between the stages, and once it is set the step
/// ends with [`SimError::Stopped`] (the caller restores the state, as for any error).
pub fn step(
    model: &Model,
    options: &StepOptions,
    state: &mut State,
    (step_index, stop): (u64, StopRequest<'_>),
    data: &mut StepData,
    controller: &mut dyn Controller,
) -> Result<(), SimError> {
    let at = StepAt { step: step_index, time: state.t };
    state.validate(model).in_step(at)?;
    stop.check(at)?;
    data.report = StepReport { step: step_index, time: state.t, ..StepReport::default() };
    let mut clock = StageClock::start();
    if data.take_over_carried() == Carried::Stale {
        kinematics(model, state, data);
        clock.lap(Stage::Kinematics);
        data.report.detection = detect_contacts(model, options, state.t, data).in_step(at)?;
        stop.check(at)?;
    }
    measure_penetration(data);
    clock.lap(Stage::DetectContacts);
    control(model, options, state, data, controller);
    clock.lap(Stage::Control);
    dynamics(model, options, state, data);
    clock.lap(Stage::Dynamics);
    stop.check(at)?;
    build_rows(model, options, state, data);
    clock.lap(Stage::BuildRows);
    stop.check(at)?;
    solve_and_resolve(model, options, state, data, stop).in_step(at)?;
    require_solved(data, at)?;
    clock.lap(Stage::Solve);
    stop.check(at)?;
    if data.internal_forces_due {
        internal_forces(model, options, state, data);
    }
    clock.lap(Stage::InternalForces);
    hagfish_tree::integrate(state, data.solver.velocity(), options.time_step).in_step(at)?;
    clock.lap(Stage::Integrate);
    stop.check(at)?;
    let end = check_result(model, options, state, data).in_step(at)?;
    clock.lap(Stage::Check);
    data.report.timings = clock.timings();
    match options.acceptance.judge(&end) {
        None => Ok(()),
        Some(rejection) => Err(SimError::StepRejected { step: at.step, time: at.time, rejection }),
    }
}

/// The velocity solve's answer is usable, or the step fails with its status.
fn require_solved(data: &StepData, at: StepAt) -> Result<(), SimError> {
    let status = data.report.solve.status;
    if status.is_solved() {
        return Ok(());
    }
    Err(SimError::SolveFailed { step: at.step, time: at.time, status, rows: data.rows.len() })
}

/// Last stage: the kinematics and contacts of the step's result `state` (carried over to the
/// next step, and the kinematics in `data.tree`), and what its acceptance is judged on. The
/// contacts of the step's start stay in `data` for the report.
pub fn check_result(
    model: &Model,
    options: &StepOptions,
    state: &State,
    data: &mut StepData,
) -> Result<EndOfStep, hagfish_geometry::GeometryError> {
    kinematics(model, state, data);
    let (detected, penetration) = data.with_carried(|data| {
        let detected = detect_contacts(model, options, state.t, data);
        (detected, penetration(data))
    });
    data.carried.detection = detected?;
    data.carried.status = Carried::Current;
    let solve = &data.report.solve;
    let inexact = solve.status == SolveStatus::SolvedInexact;
    Ok(EndOfStep {
        self_penetration_relative: penetration.self_relative,
        wall_penetration_relative: penetration.wall_relative,
        limit_excess: limit_excess(model, &state.q),
        joint_rate: rotation_rate(model, &state.qdot),
        grip_error_cm: grip_error(model, options, data),
        inexact_residual: inexact.then_some(solve.residuals.worst_relative),
    })
}

/// How far the step left a pull's gripped end from its target (cm; 0 without a grip): the
/// tail end now ([`tail_end`], the grip's point) against the step's target moved on by h at
/// its velocity. `data` must hold the kinematics of the step's end.
fn grip_error(model: &Model, options: &StepOptions, data: &StepData) -> f64 {
    let Some(grip) = data.actuation.grip else { return 0.0 };
    let (_, end, _) = tail_end(model, &data.tree);
    end.distance(grip.target + options.time_step * grip.velocity)
}

/// The largest excess of a joint angle in `q` over its limits (rad, 0 when all are within;
/// NaN for a non-finite angle).
pub fn limit_excess(model: &Model, q: &[f64]) -> f64 {
    max_or_nan(model.dofs().iter().zip(q).map(|(d, q)| (d.lower - q).max(q - d.upper)))
}

/// The largest rotation rate |q̇ᵢ| in `qdot` (rad/s, 0 without rotations; NaN for a
/// non-finite rate). A translation's rate (cm/s) is not a sign of a chain's instability and
/// is left out, unless it is not finite.
fn rotation_rate(model: &Model, qdot: &[f64]) -> f64 {
    let rates = model.joints().iter().flat_map(|joint| {
        let translates = joint.kind.translates();
        joint.dofs().map(move |a| match translates {
            true if qdot[a].is_finite() => 0.0,
            true => f64::NAN,
            false => qdot[a].abs(),
        })
    });
    max_or_nan(rates)
}

/// The largest of `values` and 0, or NaN if any is NaN (`f64::max` would drop it, and a
/// non-finite state must not pass as within bounds).
fn max_or_nan(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |worst, v| if v.is_nan() || worst.is_nan() { f64::NAN } else { worst.max(v) })
}

/// Stage 6 with its re-solves: solve; then, while something changed (a velocity-product
/// refresh is due, a contact gap is predicted to end below its target — checked after the
/// first solve only —, or a joint would overshoot a limit without a row), solve again, at most
/// `MAX_RESOLVES` (4) more times; the last solve's multipliers are kept, by what each row
/// constrains, for the next step's start (`warm_start.rs`). Re-solves where only f̃ or the bounds changed keep the
/// factor of M̃ and the contact-space matrices (one [`hagfish_solver::Factored`] handle);
/// limit rows added for overshooting joints start a new one. If raised contact bounds leave
/// the last solve without a solution, the step is solved once more with the first-order
/// bounds (the rows' own right-hand sides, which the prediction never changes). Every solve
/// polls `stop` ([`hagfish_solver::SolverError::Stopped`] once it is set).
pub fn solve_and_resolve(
    model: &Model,
    options: &StepOptions,
    state: &State,
    data: &mut StepData,
    stop: StopRequest<'_>,
) -> Result<(), hagfish_solver::SolverError> {
    // M̃ leaves the tree's data while a factor borrows it, so that the velocity-product
    // refresh can write the rest of that data between solves (two buffer swaps, no copy).
    std::mem::swap(&mut data.tree.effective_mass, &mut data.effective_mass);
    let solved = solve_with_resolves(model, options, state, data, stop);
    std::mem::swap(&mut data.tree.effective_mass, &mut data.effective_mass);
    let contacts = (&data.self_contacts[..], &data.wall_contacts[..]);
    data.warm_start.keep(&data.rows, contacts, data.solver.multipliers());
    solved
}

/// [`solve_and_resolve`] with M̃ in `data.effective_mass`.
fn solve_with_resolves(
    model: &Model,
    options: &StepOptions,
    state: &State,
    data: &mut StepData,
    stop: StopRequest<'_>,
) -> Result<(), hagfish_solver::SolverError> {
    let StepData {
        tree,
        effective_mass,
        tree_factor,
        rows,
        bounds,
        solver,
        predictor,
        velocity_guess,
        self_contacts,
        skin,
        report,
        ..
    } = data;
    let (h, margin, push_out) = (options.time_step, options.limit_margin, options.push_out);
    bounds.clear();
    bounds.extend_from_slice(rows.rhs());
    let mut round = 0;
    loop {
        let mass = backend::mass(effective_mass, tree_factor)?;
        let mut factored = solver.factor(mass, rows)?.stop_when(stop.flag());
        report.solve = *factored.solve(&tree.effective_momentum, bounds)?;
        let mut overshooting = false;
        while round < MAX_RESOLVES {
            let refreshed = round < options.velocity_product_iterations;
            let velocity = factored.workspace().velocity();
            // After the first solve only: repeated, the prediction can feed on its own faster
            // velocities (docs/physics.md).
            let raised = if round == 0 {
                predictor.tighten_contact_bounds(
                    model,
                    options,
                    state,
                    velocity,
                    self_contacts,
                    skin,
                    factored.rows(),
                    bounds,
                )
            } else {
                0
            };
            report.predicted_contact_rows += raised;
            if refreshed {
                refresh_velocity_products(model, options, state, velocity, velocity_guess, tree);
            }
            round += 1;
            overshooting = overshoots_limit(model, state, velocity, h, margin);
            if overshooting || !(refreshed || raised > 0) {
                break;
            }
            // Only f̃ or bounds changed: the factor of M̃ and the contact-space matrices stay.
            report.solve = *factored.solve(&tree.effective_momentum, bounds)?;
        }
        if !overshooting {
            break;
        }
        let first_new = rows.len();
        add_overshooting_limit_rows(model, state, solver.velocity(), h, margin, push_out, rows);
        bounds.extend_from_slice(&rows.rhs()[first_new..]);
    }
    if report.predicted_contact_rows > 0 && !report.solve.status.is_solved() {
        // The raised bounds left no solution: solve with the first-order bounds instead.
        report.predicted_contact_rows = 0;
        let mass = backend::mass(effective_mass, tree_factor)?;
        let mut factored = solver.factor(mass, rows)?.stop_when(stop.flag());
        report.solve = *factored.solve(&tree.effective_momentum, rows.rhs())?;
    }
    Ok(())
}

/// The deepest penetrations of the contacts in `data`'s contact fields (those of the step's
/// start, or of its end while [`check_result`] has the carried ones in their place).
#[derive(Debug, Clone, Copy, Default)]
struct Penetration {
    /// Self, cm.
    self_cm: f64,
    /// Self, relative to the local radius `(r_a + r_b)/2`.
    self_relative: f64,
    /// The skins' compression, fraction of their thickness.
    skin_compression: f64,
    /// Wall, cm.
    wall_cm: f64,
    /// Wall, relative to the body's radius.
    wall_relative: f64,
}

fn penetration(data: &StepData) -> Penetration {
    let mut deepest = Penetration::default();
    for contact in &data.self_contacts {
        let mut depth = (-contact.gap).max(0.0);
        let mut radius =
            0.5 * (data.centreline.radius(contact.u_a) + data.centreline.radius(contact.u_b));
        if let Some(skin) = data.skin.at(contact, &data.centreline) {
            depth = (-skin.core_gap).max(0.0);
            radius -= 0.5 * skin.thickness;
            deepest.skin_compression = deepest.skin_compression.max(skin.compression(contact.gap));
        }
        deepest.self_cm = deepest.self_cm.max(depth);
        deepest.self_relative = deepest.self_relative.max(depth / radius);
    }
    for contact in &data.wall_contacts {
        deepest.wall_cm = deepest.wall_cm.max(-contact.gap);
        deepest.wall_relative = deepest.wall_relative.max(-contact.gap / contact.radius);
    }
    deepest
}

fn measure_penetration(data: &mut StepData) {
    let deepest = penetration(data);
    let report = &mut data.report;
    report.self_contacts = data.self_contacts.len();
    report.wall_contacts = data.wall_contacts.len();
    report.max_self_penetration = deepest.self_cm;
    report.max_self_penetration_relative = deepest.self_relative;
    report.max_skin_compression = deepest.skin_compression;
    report.max_wall_penetration = deepest.wall_cm;
}

#[cfg(test)]
mod tests {
    use super::max_or_nan;

    #[test]
    fn a_nan_anywhere_makes_the_maximum_nan() {
        assert_eq!(max_or_nan([1.0, 3.0, 2.0].into_iter()), 3.0);
        assert_eq!(max_or_nan([-1.0, -2.0].into_iter()), 0.0);
        assert!(max_or_nan([1.0, f64::NAN, 5.0].into_iter()).is_nan(), "NaN then a larger value");
        assert!(max_or_nan([f64::NAN].into_iter()).is_nan());
    }
}
