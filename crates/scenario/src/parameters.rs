//! Every parameter of a scenario file, with its unit, default and meaning: the one table that
//! `hagfish params` prints. A test keeps it true to the scenario types: every field and variant
//! of a serialized scenario has a row, and every row names a field or variant that exists.
//!
//! Names are paths in the file: `drag.quadratic_g_per_cm3` is a field of `drag`,
//! `Form.steps[].Move.speed` a field of a `Move` step in a `Form` phase's `steps`.

/// One scenario parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parameter {
    /// Path of the field or variant in the scenario file.
    pub name: &'static str,
    /// Unit (CGS), or `-` for names, paths, lists and variants.
    pub unit: &'static str,
    /// The default when the field is left out, or `required`.
    pub default: &'static str,
    /// What it does.
    pub meaning: &'static str,
}

const fn p(
    name: &'static str,
    unit: &'static str,
    default: &'static str,
    meaning: &'static str,
) -> Parameter {
    Parameter { name, unit, default, meaning }
}

/// The scenario parameters, in file order.
#[rustfmt::skip]
pub const PARAMETERS: &[Parameter] = &[
    p("name", "-", "required", "short name of the scenario, used in outputs"),
    p("body", "path", "required", "body RON file (hagfish Biometrics or Rod), relative to the scenario file"),
    p("time_step_s", "s", "required", "time step h of the implicit integrator, > 0"),
    p("duration_s", "s", "required", "simulated time, > 0"),
    p("end_after_phases", "-", "false", "end the run (with a frame) once the last phase is over, e.g. a load has settled"),
    p("record_every_s", "s", "0.1", "interval between recorded frames, in whole time steps; frame 0 is the initial state"),
    p("observe_every_s", "s", "0.1", "interval of the controller's knot observations (tie end, \
       core_* end conditions), in whole time steps; apart from record_every_s so recording does not change the run"),
    p("drag", "-", "None", "water drag on every body: Some((...)) or None for vacuum"),
    p("drag.linear_dyn_s_per_cm3", "dyn·s/cm³", "required in drag", "linear (viscous) drag per projected area 2rℓ, ≥ 0"),
    p("drag.quadratic_g_per_cm3", "g/cm³", "required in drag", "quadratic drag ½ρC_d per projected area, ≥ 0 (water: 0.5)"),
    p("initial_shape", "-", "None", "the body's shape at t = 0: Some(OpenTorusKnot((...))), Some(Polyline((...))) or None (straight along +X)"),
    p("initial_shape.OpenTorusKnot", "-", "-", "an open (2, q) torus knot: head line along +X, the knot, tail line along +X"),
    p("initial_shape.OpenTorusKnot.crossings", "-", "required", "q of the open (2, q) torus knot, odd ≥ 3: 3 trefoil, 5 cinquefoil"),
    p("initial_shape.OpenTorusKnot.radius_l", "L", "required", "the torus' major radius R₀ (its minor radius is R₀/2)"),
    p("initial_shape.OpenTorusKnot.start_l", "L", "required", "the straight head part before the knot, ≥ 3(R₀ + R₀/2)/L (off the wall)"),
    p("initial_shape.OpenTorusKnot.mirror", "-", "false", "the mirror image (z → −z)"),
    p("initial_shape.Polyline", "-", "-", "a curve from a vertex file, its first vertex at the head and first segment along +X, straight on past its end"),
    p("initial_shape.Polyline.file", "-", "required", "the vertex file, relative to the scenario file: a vertex per line, x y z first (blanks or commas)"),
    p("initial_shape.Polyline.cm_per_unit", "cm", "1", "centimetres per unit of the file (100 for metres)"),
    p("skin", "-", "None", "a skin for the body in place of the body file's: Some((...)) or None (the body file's own)"),
    p("skin.thickness_fraction", "-", "required in skin", "the compressible layer's thickness, fraction of the local radius, in (0, 1)"),
    p("skin.pressure_dyn_per_cm2", "dyn/cm²", "required in skin", "pressure under the skin: a crossing compressed by δ pushes π·p·√(r_a r_b)·δ"),
    p("phases", "-", "required", "the phases of control, in order; passive after the last"),
    p("friction", "-", "None", "Coulomb friction on the self contacts' cores and the wall: Some((coefficient: μ)) or None (frictionless)"),
    p("friction.coefficient", "-", "required in friction", "μ, static = kinetic, ≥ 0 (0: frictionless, bit for bit)"),
    p("friction.edges", "-", "8", "edges E of the friction cone's inscribed pyramid, 3 to 16: the limit within 1 − cos(π/E) of Coulomb's"),
    p("friction.cone", "-", "Pyramid", "Pyramid (the fast path) or Exact: the cone itself, solved by the clarabel backend (the run switches to it; 7–40 ms a step): the reference"),
    p("obstacles", "-", "[]", "rigid obstacles, still, moving on a path or turning, the body touches like the wall (their contacts, rows and friction are the wall's)"),
    p("obstacles.Plane", "-", "-", "the half-space behind a plane"),
    p("obstacles.Plane.point", "cm", "required", "a point of the plane, (x, y, z)"),
    p("obstacles.Plane.normal", "-", "required", "the normal toward the free side, (x, y, z), any length but 0"),
    p("obstacles.Sphere", "-", "-", "a solid sphere"),
    p("obstacles.Sphere.centre", "cm", "required", "its centre, (x, y, z)"),
    p("obstacles.Sphere.radius", "cm", "required", "its radius, > 0"),
    p("obstacles.Cylinder", "-", "-", "a solid circular cylinder"),
    p("obstacles.Cylinder.point", "cm", "required", "a point of its axis, the middle of a finite one, (x, y, z)"),
    p("obstacles.Cylinder.axis", "-", "required", "its axis direction, (x, y, z), any length but 0"),
    p("obstacles.Cylinder.radius", "cm", "required", "its radius, > 0"),
    p("obstacles.Cylinder.half_length", "cm", "None", "half its length: Some(H) (> 0), or None for an infinite cylinder"),
    p("obstacles.Moving", "-", "-", "an obstacle moving on a path: Moving(shape: Sphere(..), path: [(t, (x, y, z)), ...])"),
    p("obstacles.Moving.shape", "-", "required", "a Plane, Sphere or Cylinder as posed at offset zero"),
    p("obstacles.Moving.path", "s, cm", "required", "(time, offset) waypoints at increasing times, linear between them, held beyond the ends ([] for one that stays where its shape is)"),
    p("obstacles.Moving.spin", "-", "None", "a turn at a constant rate about an axis through the shape's reference point: about an axis of its symmetry (sphere: any, cylinder: its axis, plane: its normal) it moves the surface and not the shape; about another the shape turns too (a tilting plane)"),
    p("obstacles.Moving.spin.axis", "-", "required", "the axis direction (any length but zero), right-handed with the rate"),
    p("obstacles.Moving.spin.rate_rad_per_s", "rad/s", "required", "the angular speed"),
    p("obstacles.Moving.spin.until_s", "s", "None", "when the turn stops: the obstacle holds the pose it has then (a plane tilted to an angle and held); None: it never stops"),
    p("obstacle_groove", "-", "Some(0.05)", "how finely obstacles see the tube: the deepest groove an obstacle's edge may reach unseen between two of the points they touch, fraction of the local radius, in (0, 1] (segments long against their radius are sampled between their centres); None: the bodies' spheres alone"),
    p("contact_margin_cm", "cm", "0.1", "the self contacts' speculative margin: strands closer than it are contact rows; must cover their approach in one step, wider only adds slack rows, > 0"),
    p("backend", "-", "SparseMaximal", "velocity-step linear algebra: SparseMaximal (linear in the bodies), or DenseReduced"),
    p("acceptance", "-", "(...)", "when a step's result is kept; a rejected step is retried with substeps"),
    p("acceptance.max_self_penetration_relative", "-", "0.1", "deepest self penetration at a step's end, fraction of the local radius"),
    p("acceptance.max_wall_penetration_relative", "-", "0.1", "deepest wall penetration at a step's end, fraction of the body's radius"),
    p("acceptance.max_limit_excess_deg", "°", "2", "largest joint-limit excess at a step's end"),
    p("acceptance.max_inexact_residual", "-", "1e-4", "largest relative KKT residual accepted from an inexact velocity solve"),
    p("acceptance.max_joint_rate_rad_s", "rad/s", "100", "largest joint rate at a step's end (a chain blowing up passes 500 within 0.2 s)"),
    p("acceptance.max_grip_error_cm", "cm", "None", "largest distance of a pull's gripped end from its target at a step's end (the position update's drift), Some(cm) > 0; None: not bounded"),
    p("acceptance.max_halvings", "-", "4", "a rejected step is retried as 2, 4, … 2^k substeps; then the run stops (exit 3)"),
    p("acceptance.resolve_contacts", "-", "true", "a rejected step is first retried whole with self contacts kept every 1.5 bodies (fine chains)"),
    p("phases[].Form", "-", "-", "phase: scripted knot forming with a PD pull on the tail; ends after its last step"),
    p("Form.gains", "-", "required", "gains and cap of the PD pull on the last body"),
    p("Form.gains.kp_dyn_per_cm", "dyn/cm", "required", "proportional gain of the tail pull (typical 200)"),
    p("Form.gains.kd_dyn_s_per_cm", "dyn·s/cm", "required", "derivative gain of the tail pull, implicit (typical 20)"),
    p("Form.gains.max_force_dyn", "dyn", "required", "cap on the explicit tail force (typical 2000)"),
    p("Form.steps", "-", "required", "the script: Move and Hold steps; the target is held after the last"),
    p("Form.steps[].Move", "-", "-", "step: move the tail target in a straight line at constant speed"),
    p("Form.steps[].Move.to", "-", "required", "waypoint, resolved from the body's shape when the move starts"),
    p("Form.steps[].Move.speed", "cm/s", "required", "speed of the target, > 0"),
    p("Form.steps[].Hold", "s", "-", "step: keep the target still for this long"),
    p("Move.to.Point", "cm", "-", "waypoint: a fixed world point (x, y, z)"),
    p("Move.to.FromBody", "-", "-", "waypoint: an offset from the centre of a body"),
    p("Move.to.FromBody.body", "-", "required", "body index, 0 = head"),
    p("Move.to.FromBody.offset", "cm", "required", "offset (x, y, z) from that body's centre"),
    p("Move.to.FromTarget", "cm", "-", "waypoint: an offset (x, y, z) from the end of the previous move"),
    p("Move.to.FromLoopCentroid", "cm", "-", "waypoint: an offset from the centroid of the largest loop seen from above"),
    p("Move.to.BodyLengths", "L", "-", "waypoint: a world point (x, y, z) in body lengths"),
    p("Move.to.FromArc", "-", "-", "waypoint: an offset from the body at a fraction of L"),
    p("Move.to.FromArc.at", "L", "required", "fraction of the body length from the head, in [0, 1]"),
    p("Move.to.FromArc.offset_radii", "r", "required", "offset (x, y, z) in that body's radii"),
    p("Move.to.FromLoopCentroidRadii", "r", "-", "waypoint: FromLoopCentroid with the offset in mean body radii"),
    p("Move.to.FromTargetRadii", "r", "-", "waypoint: FromTarget with the offset in mean radii"),
    p("phases[].Tie", "-", "-", "phase: tie a knot by control from the body's state; ends once the analysis shows it"),
    p("Tie.knot", "-", "required", "the knot to tie"),
    p("Tie.knot.Trefoil", "-", "-", "knot: the overhand knot 3_1, Right or Left (sign of its writhe)"),
    p("Tie.at", "L", "required", "crossover at this fraction of the body length from the head"),
    p("Tie.min_tail_d", "D", "None", "Some(d): the crossover moves head-ward where `at` leaves < d local diameters tail-ward"),
    p("Tie.gains", "-", "(200, 20, 2000)", "gains and cap of the PD tail pull (as Form.gains)"),
    p("Tie.speed_cm_s", "cm/s", "5", "speed of the tail's target"),
    p("Tie.retry_speed_cm_s", "cm/s", "None", "Some(v): the tail's target speed on attempts after the first (default speed_cm_s)"),
    p("Tie.attempts", "-", "2", "plans tried before the phase fails (exit 4, status tie_failed)"),
    p("Tie.hold_s", "s", "0.5", "how long the knot must be shown before the phase ends"),
    p("Tie.settle_s", "s", "2", "how long after a plan the knot may take to show"),
    p("phases[].Follow", "-", "-", "phase: tie a knot by following the leader: the tail's tip runs along a template, the body follows its path"),
    p("Follow.template", "-", "required", "the knot's template: a curve of the knot the tail's tip runs along"),
    p("Follow.template.file", "-", "required", "the template's vertex file (x y z in tube diameters), relative to the scenario file"),
    p("Follow.template.knot", "-", "required", "the Rolfsen name the knot analysis must show (\"6_2\")"),
    p("Follow.template.handedness", "-", "None", "Some(Right | Left): the core's handedness the template ties as written, checked"),
    p("Follow.template.mirror", "-", "false", "tie the mirror image (z negated, handedness flipped)"),
    p("Follow.template.diameters_per_unit", "D", "1", "body diameters per template unit (< 1: tighter than the tube, compressing a skin)"),
    p("Follow.speed_cm_s", "cm/s", "2", "speed of the tail's tip along the template"),
    p("Follow.servo", "-", "(2000, 20)", "the joint servos' gains, per DOF"),
    p("Follow.servo.stiffness_dyn_cm_per_rad", "dyn·cm/rad", "2000", "servo stiffness k: τ = k(q* − q) − c(q̇ − q̇*)"),
    p("Follow.servo.damping_dyn_cm_s_per_rad", "dyn·cm·s/rad", "20", "servo damping c"),
    p("Follow.hold_s", "s", "0.5", "how long the knot must be shown before the phase ends"),
    p("Follow.settle_s", "s", "2", "how long after the template the knot may take to show (then exit 4)"),
    p("phases[].Hold", "s", "-", "phase: keep the last forming target for this long; otherwise passive"),
    p("phases[].Thigmotaxis", "-", "-", "phase: thigmotaxic inverse dynamics on the first and last self contact"),
    p("Thigmotaxis.name", "-", "\"thigmo\"", "name in the phase column of the outputs, e.g. tighten, loosen, slide"),
    p("Thigmotaxis.parameters", "-", "required", "targets, tail pull and force cap"),
    p("Thigmotaxis.parameters.head", "-", "required", "sliding targets at the first (head-most) contact"),
    p("Thigmotaxis.parameters.tail", "-", "required", "sliding targets at the last (tail-most) contact"),
    p("Thigmotaxis.parameters.{head,tail}.v_a", "cm/s", "required", "anterior strand slides tail-ward \
       relative to the other at least this fast (negative: head-ward, the knot moves tail-ward)"),
    p("Thigmotaxis.parameters.{head,tail}.v_b", "cm/s", "required", "posterior strand slides tail-ward \
       relative to the other at least this fast (negative: head-ward)"),
    p("Thigmotaxis.parameters.tail_pull_dyn", "dyn", "required", "force on the last body along its tangent, tail-ward"),
    p("Thigmotaxis.parameters.max_force_dyn", "dyn", "required", "largest force of one thigmotaxis row (its slack penalty)"),
    p("Thigmotaxis.parameters.force_space", "-", "Full", "the torques the rows may exert: Full (every DOF), BendingOnly (no twist torque) \
       or Modes((file, kind, modes)) (the span of the first k mode shapes of a force field)"),
    p("Thigmotaxis.parameters.force_space.Modes", "-", "-", "P = BBᵀ, B the first k shapes of modes.csv resampled at this body's DOFs, orthonormalised"),
    p("Thigmotaxis.parameters.force_space.Modes.file", "-", "required", "a modes.csv of hagfish modes, relative to the scenario file"),
    p("Thigmotaxis.parameters.force_space.Modes.kind", "-", "required", "the selection whose shapes are read: all, bend, bend-y, bend-z or twist \
       (the DOFs of other kinds are zero in every mode)"),
    p("Thigmotaxis.parameters.force_space.Modes.modes", "-", "required", "k ≥ 1, at most the file's modes of that kind"),
    p("Thigmotaxis.parameters.replay", "-", "None", "Some((file: FILE)): open-loop replay, the field of FILE (hagfish modes --replay) applied as \
       joint torques at the time since the phase began, instead of the rows (the tail pull stays)"),
    p("Thigmotaxis.parameters.replay.file", "-", "required", "a replay CSV of hagfish modes (time_s, one column per DOF), relative to the scenario file"),
    p("Thigmotaxis.until", "-", "required", "end conditions; the phase ends at the first that holds"),
    p("Thigmotaxis.until.seconds", "s", "required", "longest duration of the phase"),
    p("Thigmotaxis.until.hold_s", "s", "0", "a condition of when must hold this long without interruption to end the phase"),
    p("Thigmotaxis.until.when", "-", "[]", "conditions (QUANTITY, Below|Above, THRESHOLD), any of which ends the phase \
       once held for hold_s, e.g. [(Span, Below, D(12.6))]; QUANTITY: KnotStart (Cm, L), Span (Cm, L, D), \
       CoreStart (L), CoreLength (D), CoreGrowth and CoreShrink (Above, Fraction), KineticEnergy (Below, Erg)"),
    p("Thigmotaxis.until.when[].Cm", "cm", "-", "threshold in cm of arc length"),
    p("Thigmotaxis.until.when[].L", "L", "-", "threshold as a fraction of the body length"),
    p("Thigmotaxis.until.when[].D", "D", "-", "threshold in mean local diameters"),
    p("Thigmotaxis.until.when[].Fraction", "-", "-", "threshold as a fraction of the knotted core's length when the phase started"),
    p("Thigmotaxis.until.when[].Erg", "erg", "-", "threshold of the kinetic energy"),
    p("phases[].Load", "-", "-", "phase: a force on the tail end, ramped up; stays on after the phase"),
    p("Load.force_dyn", "dyn", "required", "magnitude once ramped, ≥ 0 (0 removes a load)"),
    p("Load.direction", "-", "required", "Fixed((x, y, z)), or TailTangent: along the last body's axis (a follower load)"),
    p("Load.direction.Fixed", "-", "-", "a fixed world direction (normalised): a dead load"),
    p("Load.ramp_s", "s", "0", "time to ramp the magnitude up from 0"),
    p("Load.until", "-", "required", "when the phase ends: fields as Thigmotaxis.until"),
    p("phases[].Pull", "-", "-", "phase: the tail end gripped (clamped) and moved at a prescribed speed; held still after the phase"),
    p("Pull.speed_cm_per_s", "cm/s", "required", "speed of the tail end, ≥ 0 (0 clamps it in place)"),
    p("Pull.direction", "-", "required", "(x, y, z): the world direction of the pull (normalised)"),
    p("Pull.ramp_s", "s", "0", "time over which the speed rises linearly from 0 (0: at once)"),
    p("Pull.until", "-", "required", "when the phase ends: fields as Thigmotaxis.until"),
];

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use hagfish_control::{
        Condition, Direction, ForceSpace, FormingScript, Handedness, KindSelection, LoadDirection,
        LoadPhase, ModalSpace, Phase, PullPhase, Quantity, Replay, ScriptStep, SlidingTargets,
        TailGains, ThigmoParameters, ThigmoPhase, Threshold, TieKnot, TiePhase, Until, WaterDrag,
        Waypoint,
    };

    use super::*;
    use crate::scenario::Scenario;

    /// The key a row documents: the last segment of its name (`v_a` for `…{head,tail}.v_a`).
    fn parameter_key(name: &str) -> &str {
        name.rsplit('.').next().unwrap_or(name)
    }

    /// A scenario using every field and every variant.
    fn everything() -> Scenario {
        let targets = SlidingTargets { v_a: 1.0, v_b: 2.0 };
        let step = |to| ScriptStep::Move { to, speed: 5.0 };
        Scenario {
            name: "all".into(),
            body: "body.ron".into(),
            time_step_s: 0.01,
            duration_s: 1.0,
            end_after_phases: true,
            record_every_s: 0.1,
            observe_every_s: 0.2,
            drag: Some(WaterDrag::default()),
            skin: Some(hagfish_anatomy::BodySkin {
                thickness_fraction: 0.25,
                pressure_dyn_per_cm2: 1000.0,
            }),
            initial_shape: Some(crate::InitialShape::OpenTorusKnot(crate::OpenTorusKnot {
                crossings: 3,
                radius_l: 0.025,
                start_l: 0.15,
                mirror: true,
            })),
            backend: hagfish_sim::DynamicsBackend::DenseReduced,
            acceptance: hagfish_sim::StepAcceptance::default(),
            friction: Some(hagfish_sim::rows::Friction::pyramid(0.1, 8)),
            obstacles: vec![
                crate::ObstacleSpec::Plane { point: [0.0, -5.0, 0.0], normal: [0.0, 1.0, 0.0] },
                crate::ObstacleSpec::Sphere { centre: [10.0, 0.0, 3.0], radius: 1.0 },
                crate::ObstacleSpec::Cylinder {
                    point: [20.0, -3.0, 0.0],
                    axis: [0.0, 0.0, 1.0],
                    radius: 2.0,
                    half_length: Some(5.0),
                },
                crate::ObstacleSpec::Moving {
                    shape: Box::new(crate::ObstacleSpec::Sphere {
                        centre: [5.0, 5.0, 0.0],
                        radius: 1.0,
                    }),
                    path: vec![(0.0, [0.0; 3]), (10.0, [20.0, 0.0, 0.0])],
                    spin: Some(crate::SpinSpec {
                        axis: [0.0, 1.0, 0.0],
                        rate_rad_per_s: 0.5,
                        until_s: Some(4.0),
                    }),
                },
            ],
            obstacle_groove: Some(0.1),
            contact_margin_cm: 0.05,
            phases: vec![
                Phase::Form(FormingScript {
                    gains: TailGains::default(),
                    steps: vec![
                        step(Waypoint::Point([1.0, 2.0, 3.0])),
                        step(Waypoint::FromBody { body: 3, offset: [0.0; 3] }),
                        step(Waypoint::FromTarget([0.0; 3])),
                        step(Waypoint::FromLoopCentroid([0.0; 3])),
                        step(Waypoint::BodyLengths([0.5, 0.2, 0.0])),
                        step(Waypoint::FromArc { at: 0.3, offset_radii: [0.0, 3.0, 3.0] }),
                        step(Waypoint::FromLoopCentroidRadii([0.0; 3])),
                        step(Waypoint::FromTargetRadii([0.0; 3])),
                        ScriptStep::Hold(1.0),
                    ],
                }),
                Phase::Hold(1.0),
                Phase::Tie(TiePhase::new(TieKnot::Trefoil(Handedness::Left), 0.31)),
                Phase::Follow(hagfish_control::FollowPhase {
                    template: hagfish_control::KnotTemplate {
                        file: "6_2.txt".into(),
                        knot: "6_2".into(),
                        handedness: Some(Handedness::Right),
                        mirror: true,
                        diameters_per_unit: 0.8,
                        vertices: None,
                    },
                    speed_cm_s: 2.0,
                    servo: hagfish_control::ServoGains::default(),
                    hold_s: 0.5,
                    settle_s: 2.0,
                    cm_per_unit: 0.0,
                }),
                Phase::Thigmotaxis(ThigmoPhase {
                    name: "slide".into(),
                    parameters: ThigmoParameters {
                        head: targets,
                        tail: targets,
                        tail_pull_dyn: 20.0,
                        max_force_dyn: 2000.0,
                        force_space: ForceSpace::BendingOnly,
                        replay: None,
                    },
                    until: Until {
                        seconds: 1.0,
                        hold_s: 0.2,
                        when: [
                            (Quantity::KnotStart, Direction::Below, Threshold::Cm(3.0)),
                            (Quantity::Span, Direction::Above, Threshold::L(0.7)),
                            (Quantity::Span, Direction::Below, Threshold::D(12.0)),
                            (Quantity::CoreGrowth, Direction::Above, Threshold::Fraction(0.3)),
                            (Quantity::KineticEnergy, Direction::Below, Threshold::Erg(1e-6)),
                        ]
                        .into_iter()
                        .map(|c| Condition::try_from(c).expect("admitted"))
                        .collect(),
                    },
                }),
                Phase::Thigmotaxis(ThigmoPhase {
                    name: "modal".into(),
                    parameters: ThigmoParameters {
                        head: targets,
                        tail: targets,
                        tail_pull_dyn: 20.0,
                        max_force_dyn: 2000.0,
                        force_space: ForceSpace::Modes(ModalSpace {
                            file: "modes.csv".into(),
                            kind: KindSelection::Bend,
                            modes: 4,
                            basis: None,
                        }),
                        replay: Some(Replay { file: "replay.csv".into(), field: None }),
                    },
                    until: Until { seconds: 1.0, ..Until::default() },
                }),
                Phase::Load(LoadPhase {
                    force_dyn: 1.0,
                    direction: LoadDirection::Fixed((0.0, 1.0, 0.0)),
                    ramp_s: 0.5,
                    until: Until { seconds: 1.0, ..Until::default() },
                }),
                Phase::Pull(PullPhase {
                    speed_cm_per_s: 0.5,
                    direction: (1.0, 0.0, 0.0),
                    ramp_s: 0.5,
                    until: Until { seconds: 1.0, ..Until::default() },
                }),
                Phase::Load(LoadPhase {
                    force_dyn: 1.0,
                    direction: LoadDirection::TailTangent,
                    ramp_s: 0.5,
                    until: Until { seconds: 1.0, ..Until::default() },
                }),
            ],
        }
    }

    /// Identifiers followed by `:` (fields) or `(` (variants and struct names) in RON text.
    fn identifiers(text: &str) -> BTreeSet<String> {
        let mut found = BTreeSet::new();
        let mut word = String::new();
        for c in text.chars() {
            if c.is_alphanumeric() || c == '_' {
                word.push(c);
                continue;
            }
            if (c == ':' || c == '(') && word.starts_with(|w: char| w.is_alphabetic()) {
                found.insert(std::mem::take(&mut word));
            }
            word.clear();
        }
        found
    }

    #[test]
    fn every_field_and_variant_has_a_row_and_every_row_exists() {
        let mut other = everything();
        other.initial_shape = Some(crate::InitialShape::Polyline(crate::PolylineShape {
            file: "curve.txt".into(),
            cm_per_unit: 100.0,
            vertices: None,
        }));
        let text = [everything(), other]
            .iter()
            .map(|s| ron::ser::to_string(s).expect("plain data serializes"))
            .collect::<String>();
        let keys: BTreeSet<&str> = PARAMETERS.iter().map(|p| parameter_key(p.name)).collect();
        let found = identifiers(&text);
        assert!(found.len() > 20, "{found:?}");
        for identifier in found.iter().filter(|i| *i != "Some") {
            assert!(keys.contains(identifier.as_str()), "{identifier} has no row in PARAMETERS");
        }
        for key in &keys {
            assert!(found.contains(*key), "row {key} names no field or variant");
        }
    }

    #[test]
    fn the_defaults_in_the_table_are_the_loaders() {
        let text = "(name: \"x\", body: \"b.ron\", time_step_s: 0.01, duration_s: 1.0, \
                    phases: [Thigmotaxis((parameters: (head: (v_a: 0.0, v_b: 0.0), \
                    tail: (v_a: 0.0, v_b: 0.0), tail_pull_dyn: 0.0, max_force_dyn: 1.0), \
                    until: (seconds: 1.0)))])";
        let scenario: Scenario = ron::from_str(text).expect("a minimal scenario parses");
        let default =
            |name: &str| PARAMETERS.iter().find(|p| p.name == name).map(|p| p.default).expect(name);
        assert_eq!(default("record_every_s").parse::<f64>().ok(), Some(scenario.record_every_s));
        let observe_every = default("observe_every_s").parse::<f64>().ok();
        assert_eq!(observe_every, Some(scenario.observe_every_s));
        assert_eq!(default("drag"), "None");
        assert_eq!(default("backend"), format!("{:?}", scenario.backend));
        let margin = default("contact_margin_cm").parse::<f64>().ok();
        assert_eq!(margin, Some(scenario.contact_margin_cm));
        assert!(scenario.drag.is_none());
        let Some(Phase::Thigmotaxis(phase)) = scenario.phases.first() else {
            panic!("one thigmotaxis phase")
        };
        assert_eq!(default("Thigmotaxis.until.when"), "[]");
        assert!(phase.until.when.is_empty());
        assert_eq!(default("Thigmotaxis.name"), format!("{:?}", phase.name));
        let drag = WaterDrag::default();
        assert_eq!(drag.quadratic_g_per_cm3, 0.5);
    }
}
