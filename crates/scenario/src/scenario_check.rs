//! Checks of a scenario's values after parsing, each failure reported at the value's
//! `file:line:column`: times and speeds positive, gains and drag non-negative, every number
//! finite, body indices inside the body.
//!
//! Keys used many times (the `speed` of every `Move`, the `v_a` of every contact) are located
//! by their occurrence in file order, which is the order of the checks below as long as the
//! fields of each struct keep the documented order (head before tail). A value out of order
//! is still named, only its position may point at a sibling.

use std::collections::HashMap;

use hagfish_anatomy::{AnatomyError, DataFile, Field};
use hagfish_control::{
    FollowPhase, ForceSpace, FormingScript, LoadDirection, LoadPhase, Phase, PullPhase, Quantity,
    ScriptStep, TailGains, ThigmoPhase, Threshold, TiePhase, Until, Waypoint,
};

use crate::initial_shape::{InitialShape, OpenTorusKnot};
use crate::scenario::{MIN_TIME_STEP_S, Scenario};

/// What a value must be.
#[derive(Clone, Copy)]
enum Range {
    AtLeast(f64),
    AtMost(f64),
    Fraction,
    /// In (0, 1): a part of something other than the body length.
    Proportion,
    Positive,
    NonNegative,
    Finite,
}

impl Range {
    fn holds(self, value: f64) -> bool {
        value.is_finite()
            && match self {
                Range::AtLeast(floor) => value >= floor,
                Range::AtMost(cap) => value <= cap,
                Range::Fraction => (0.0..=1.0).contains(&value),
                Range::Proportion => value > 0.0 && value < 1.0,
                Range::Positive => value > 0.0,
                Range::NonNegative => value >= 0.0,
                Range::Finite => true,
            }
    }

    fn expected(self) -> String {
        match self {
            Range::AtLeast(floor) => format!("finite and ≥ {floor:e}"),
            Range::AtMost(cap) => format!("at most {cap}"),
            Range::Fraction => "a fraction of the body length in [0, 1]".into(),
            Range::Proportion => "a proportion in (0, 1)".into(),
            Range::Positive => "finite and > 0".into(),
            Range::NonNegative => "finite and ≥ 0".into(),
            Range::Finite => "finite".into(),
        }
    }
}

/// Walks the values in file order, counting the occurrences of each key.
struct Checker<'a> {
    file: &'a DataFile<Scenario>,
    seen: HashMap<&'static str, usize>,
}

impl Checker<'_> {
    /// The next occurrence of `key` in file order.
    fn next_field(&mut self, key: &'static str) -> Field {
        let count = self.seen.entry(key).or_insert(0);
        let field = Field::nth(key, *count);
        *count += 1;
        field
    }

    /// Checks the value of the next occurrence of `key`.
    fn check(&mut self, key: &'static str, value: f64, range: Range) -> Result<(), AnatomyError> {
        let field = self.next_field(key);
        if range.holds(value) {
            return Ok(());
        }
        Err(AnatomyError::OutOfRange {
            at: self.file.locate(&field),
            field,
            value,
            expected: range.expected(),
        })
    }

    /// Checks the three coordinates of the next occurrence of `key` (a point or offset).
    fn check_vector(&mut self, key: &'static str, v: [f64; 3]) -> Result<(), AnatomyError> {
        let field = self.next_field(key);
        match v.into_iter().find(|x| !x.is_finite()) {
            None => Ok(()),
            Some(value) => Err(AnatomyError::OutOfRange {
                at: self.file.locate(&field),
                field,
                value,
                expected: "finite coordinates (cm)".into(),
            }),
        }
    }

    fn gains(&mut self, gains: &TailGains) -> Result<(), AnatomyError> {
        self.check("kp_dyn_per_cm", gains.kp_dyn_per_cm, Range::NonNegative)?;
        self.check("kd_dyn_s_per_cm", gains.kd_dyn_s_per_cm, Range::NonNegative)?;
        self.check("max_force_dyn", gains.max_force_dyn, Range::Positive)
    }

    fn forming(&mut self, script: &FormingScript, bodies: usize) -> Result<(), AnatomyError> {
        self.gains(&script.gains)?;
        for step in &script.steps {
            match *step {
                ScriptStep::Move { to, speed } => {
                    self.waypoint(to, bodies)?;
                    self.check("speed", speed, Range::Positive)?;
                }
                ScriptStep::Hold(seconds) => self.check("Hold", seconds, Range::NonNegative)?,
            }
        }
        Ok(())
    }

    fn waypoint(&mut self, to: Waypoint, bodies: usize) -> Result<(), AnatomyError> {
        match to {
            Waypoint::Point(p) => self.check_vector("Point", p),
            Waypoint::FromTarget(p) => self.check_vector("FromTarget", p),
            Waypoint::FromLoopCentroid(p) => self.check_vector("FromLoopCentroid", p),
            Waypoint::BodyLengths(p) => self.check_vector("BodyLengths", p),
            Waypoint::FromLoopCentroidRadii(p) => self.check_vector("FromLoopCentroidRadii", p),
            Waypoint::FromTargetRadii(p) => self.check_vector("FromTargetRadii", p),
            Waypoint::FromArc { at, offset_radii } => {
                self.check("at", at, Range::Fraction)?;
                self.check_vector("offset_radii", offset_radii)
            }
            Waypoint::FromBody { body, offset } => {
                let field = self.next_field("body");
                if body >= bodies {
                    return Err(AnatomyError::OutOfRange {
                        at: self.file.locate(&field),
                        field,
                        value: body as f64,
                        expected: format!("a body index below {bodies} (0 = head)"),
                    });
                }
                self.check_vector("offset", offset)
            }
        }
    }

    /// A tie on a body `body_diameters` local diameters long: `min_tail_d` must fit in it.
    fn tie(&mut self, phase: &TiePhase, body_diameters: f64) -> Result<(), AnatomyError> {
        self.check("at", phase.at, Range::Fraction)?;
        if let Some(diameters) = phase.min_tail_d {
            self.require(
                "min_tail_d",
                diameters,
                diameters > 0.0 && diameters < body_diameters,
                || {
                    format!(
                        "> 0 and less than the body's length, {body_diameters:.1} local diameters"
                    )
                },
            )?;
        }
        self.gains(&phase.gains)?;
        self.check("speed_cm_s", phase.speed_cm_s, Range::Positive)?;
        if let Some(retry) = phase.retry_speed_cm_s {
            self.check("retry_speed_cm_s", retry, Range::Positive)?;
        }
        self.check("attempts", f64::from(phase.attempts), Range::Positive)?;
        self.check("hold_s", phase.hold_s, Range::NonNegative)?;
        self.check("settle_s", phase.settle_s, Range::NonNegative)
    }

    fn follow(&mut self, phase: &FollowPhase) -> Result<(), AnatomyError> {
        self.check("diameters_per_unit", phase.template.diameters_per_unit, Range::Positive)?;
        self.check("speed_cm_s", phase.speed_cm_s, Range::Positive)?;
        let servo = &phase.servo;
        self.check("stiffness_dyn_cm_per_rad", servo.stiffness_dyn_cm_per_rad, Range::NonNegative)?;
        self.check("damping_dyn_cm_s_per_rad", servo.damping_dyn_cm_s_per_rad, Range::NonNegative)?;
        self.check("hold_s", phase.hold_s, Range::NonNegative)?;
        self.check("settle_s", phase.settle_s, Range::NonNegative)
    }

    fn thigmotaxis(&mut self, phase: &ThigmoPhase) -> Result<(), AnatomyError> {
        let p = &phase.parameters;
        for targets in [p.head, p.tail] {
            self.check("v_a", targets.v_a, Range::Finite)?;
            self.check("v_b", targets.v_b, Range::Finite)?;
        }
        self.check("tail_pull_dyn", p.tail_pull_dyn, Range::Finite)?;
        self.check("max_force_dyn", p.max_force_dyn, Range::Positive)?;
        if let ForceSpace::Modes(space) = &p.force_space {
            let k = space.modes;
            self.require("modes", k as f64, k >= 1, || "at least 1 mode".into())?;
        }
        self.until(&phase.until)
    }

    /// The next `key`'s value must satisfy `holds`, else it is out of range: `expected`.
    fn require(
        &mut self,
        key: &'static str,
        value: f64,
        holds: bool,
        expected: impl FnOnce() -> String,
    ) -> Result<(), AnatomyError> {
        let field = self.next_field(key);
        if holds {
            return Ok(());
        }
        Err(AnatomyError::OutOfRange {
            at: self.file.locate(&field),
            field,
            value,
            expected: expected(),
        })
    }

    /// An open torus knot that is a knot, stays off the wall and fits in the body.
    fn open_torus_knot(
        &mut self,
        knot: &OpenTorusKnot,
        length_cm: f64,
    ) -> Result<(), AnatomyError> {
        let q = knot.crossings;
        self.require("crossings", f64::from(q), q >= 3 && q % 2 == 1, || {
            "an odd number ≥ 3 (3: trefoil, 5: cinquefoil)".into()
        })?;
        let min_start = knot.min_start_l();
        self.require("start_l", knot.start_l, knot.start_l >= min_start, || {
            format!("at least 3(R₀ + a)/L = {min_start:.4}, so that the knot stays off the wall")
        })?;
        let radius = knot.radius_l;
        if !(radius.is_finite() && radius > 0.0) {
            return self.check("radius_l", radius, Range::Positive);
        }
        // The tail beyond the knot: at least the knot's own diameter, to be pulled on.
        let needed = knot.knotted_length_cm(length_cm) + 3.0 * radius * length_cm;
        self.require("radius_l", radius, needed <= length_cm, || {
            format!(
                "a knot that fits: its head line, knot and a tail of 3 R₀ take {needed:.2} cm \
                 of the body's {length_cm:.2} cm"
            )
        })
    }

    fn load(&mut self, phase: &LoadPhase) -> Result<(), AnatomyError> {
        self.check("force_dyn", phase.force_dyn, Range::NonNegative)?;
        if let LoadDirection::Fixed(direction) = phase.direction {
            self.direction("Fixed", direction)?;
        }
        self.check("ramp_s", phase.ramp_s, Range::NonNegative)?;
        self.until(&phase.until)
    }

    fn pull(&mut self, phase: &PullPhase) -> Result<(), AnatomyError> {
        self.check("speed_cm_per_s", phase.speed_cm_per_s, Range::NonNegative)?;
        self.direction("direction", phase.direction)?;
        self.check("ramp_s", phase.ramp_s, Range::NonNegative)?;
        self.until(&phase.until)
    }

    /// A direction at the next `key`: finite and not zero.
    fn direction(
        &mut self,
        key: &'static str,
        (x, y, z): (f64, f64, f64),
    ) -> Result<(), AnatomyError> {
        let field = self.next_field(key);
        let length = (x * x + y * y + z * z).sqrt();
        if length.is_finite() && length > 0.0 {
            return Ok(());
        }
        Err(AnatomyError::OutOfRange {
            at: self.file.locate(&field),
            field,
            value: length,
            expected: "a finite, non-zero direction".into(),
        })
    }

    fn until(&mut self, until: &Until) -> Result<(), AnatomyError> {
        self.check("seconds", until.seconds, Range::NonNegative)?;
        self.check("hold_s", until.hold_s, Range::NonNegative)?;
        // The end conditions in file order, each found by its unit (`D(12.6)`) with its range.
        for condition in &until.when {
            let (key, range) = match (condition.quantity(), condition.threshold()) {
                (_, Threshold::Cm(_)) => ("when.Cm", Range::Finite),
                (_, Threshold::L(_)) => ("when.L", Range::Fraction),
                (_, Threshold::D(_)) => ("when.D", Range::Positive),
                (Quantity::CoreShrink, Threshold::Fraction(_)) => {
                    ("when.Fraction", Range::Proportion)
                }
                (_, Threshold::Fraction(_)) => ("when.Fraction", Range::Positive),
                (_, Threshold::Erg(_)) => ("when.Erg", Range::NonNegative),
            };
            self.check(key, condition.threshold().value(), range)?;
        }
        Ok(())
    }
}

/// Checks every value of the scenario in `file` for a body of `bodies` bodies,
/// `body_length_cm` long and `body_diameters` local diameters long (∫ ds / 2r).
pub(crate) fn check_scenario(
    file: &DataFile<Scenario>,
    bodies: usize,
    body_length_cm: f64,
    body_diameters: f64,
) -> Result<(), AnatomyError> {
    let s = &file.value;
    let mut checker = Checker { file, seen: HashMap::new() };
    // The top-level `body:` (the biometrics file) comes before any `FromBody(body: …)`.
    checker.next_field("body");
    checker.check("time_step_s", s.time_step_s, Range::AtLeast(MIN_TIME_STEP_S))?;
    checker.check("duration_s", s.duration_s, Range::Positive)?;
    checker.check("record_every_s", s.record_every_s, Range::Positive)?;
    checker.check("observe_every_s", s.observe_every_s, Range::Positive)?;
    checker.check("contact_margin_cm", s.contact_margin_cm, Range::Positive)?;
    if let Some(drag) = s.drag {
        checker.check("linear_dyn_s_per_cm3", drag.linear_dyn_s_per_cm3, Range::NonNegative)?;
        checker.check("quadratic_g_per_cm3", drag.quadratic_g_per_cm3, Range::NonNegative)?;
    }
    if let Some(skin) = s.skin {
        checker.check("thickness_fraction", skin.thickness_fraction, Range::Proportion)?;
        checker.check("pressure_dyn_per_cm2", skin.pressure_dyn_per_cm2, Range::Positive)?;
    }
    if let Some(InitialShape::OpenTorusKnot(knot)) = &s.initial_shape {
        checker.open_torus_knot(knot, body_length_cm)?;
    }
    let a = &s.acceptance;
    for (key, value) in [
        ("max_self_penetration_relative", a.max_self_penetration_relative),
        ("max_wall_penetration_relative", a.max_wall_penetration_relative),
        ("max_limit_excess_deg", a.max_limit_excess_deg),
        ("max_inexact_residual", a.max_inexact_residual),
        ("max_joint_rate_rad_s", a.max_joint_rate_rad_s),
    ]
    .into_iter()
    .chain(a.max_grip_error_cm.map(|bound| ("max_grip_error_cm", bound)))
    {
        checker.check(key, value, Range::Positive)?;
    }
    checker.check("max_halvings", f64::from(a.max_halvings), Range::AtMost(20.0))?;
    for phase in &s.phases {
        match phase {
            Phase::Form(script) => checker.forming(script, bodies)?,
            Phase::Hold(seconds) => checker.check("Hold", *seconds, Range::NonNegative)?,
            Phase::Thigmotaxis(phase) => checker.thigmotaxis(phase)?,
            Phase::Tie(phase) => checker.tie(phase, body_diameters)?,
            Phase::Load(phase) => checker.load(phase)?,
            Phase::Pull(phase) => checker.pull(phase)?,
            Phase::Follow(phase) => checker.follow(phase)?,
        }
    }
    Ok(())
}
