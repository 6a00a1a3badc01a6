//! When a phase ends: its duration, or any of a list of conditions on the knot (where it
//! sits, how large it is) or on the body (settled), each read from what the controller
//! observes at the start of a step.
//!
//! A condition is a [`Quantity`], a [`Direction`] and a [`Threshold`] with its unit, written
//! in a scenario as a tuple:
//!
//! ```text
//! until: (seconds: 20.0, hold_s: 0.3, when: [(Span, Below, D(12.6)), (CoreStart, Below, L(0.04))])
//! ```
//!
//! ends the phase after 20 s, or once the knot's contact span has been at most 12.6 local
//! diameters, or the knotted core's head-ward end within 0.04 body lengths of the head, for
//! 0.3 s without interruption. Each quantity admits only the units it can be read in
//! ([`Quantity::admits`]); any other combination is refused when the scenario is read
//! ([`ControlError::NotACondition`]).

use serde::{Deserialize, Serialize};

use crate::error::ControlError;
use crate::knot_span::KnotSpan;

/// What an end condition looks at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Quantity {
    /// The knot's anterior end: the arc length from the head of the most anterior self
    /// contact ([`KnotSpan::start_cm`]). In [`Threshold::Cm`] or [`Threshold::L`]; `Below`
    /// ends a slide head-ward, `Above` one tail-ward.
    KnotStart,
    /// The knot's contact span, `end − start` ([`KnotSpan::length_cm`]). In
    /// [`Threshold::Cm`], [`Threshold::L`] or [`Threshold::D`] (the span over its mean local
    /// diameter, [`KnotSpan::length_d`]: a knot size that carries over to bodies of other
    /// lengths and thicknesses); `Below` ends a tightening, `Above` a loosening.
    Span,
    /// The knotted core's head-ward end (the shortest knotted sub-arc, `hagfish_knots`) of the
    /// latest observation, so it is looked at every `observe_every_s` of the scenario. In
    /// [`Threshold::L`]. Unlike [`Quantity::KnotStart`] (the first self contact, which a loop
    /// of the tail end can make near the head while the knot is still far from it), this is
    /// where the knot itself is.
    CoreStart,
    /// The knotted core's length in local diameters, of the latest observation as
    /// [`Quantity::CoreStart`]. In [`Threshold::D`]; `Above` ends a loosening, `Below` a
    /// tightening.
    CoreLength,
    /// How much longer the knotted core is than at the last observation before the phase
    /// started: `Above` a [`Threshold::Fraction`] f holds once `now ≥ (1 + f)·start` (0.3:
    /// 30 % longer), loosened relative to the knot the phase was given, whatever its size.
    CoreGrowth,
    /// How much shorter the knotted core is than when the phase started: `Above` a
    /// [`Threshold::Fraction`] f holds once `now ≤ (1 − f)·start` (0.25: a quarter shorter),
    /// tightened relative to the knot the phase was given.
    CoreShrink,
    /// The kinetic energy `½ Σ Vᵢ·IᵢVᵢ` ([`Threshold::Erg`]); `Below` ends the phase once the
    /// body has settled.
    KineticEnergy,
}

/// Which side of its threshold a quantity must be on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Direction {
    /// At most the threshold: `value ≤ threshold`.
    Below,
    /// At least the threshold: `value ≥ threshold`.
    Above,
}

/// A threshold with its unit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Threshold {
    /// Centimetres of arc length.
    Cm(f64),
    /// A fraction of the body length L (body-relative: carries over to other bodies); the
    /// threshold in cm is `fraction · L`.
    L(f64),
    /// Mean local diameters D: a size relative to the body's thickness.
    D(f64),
    /// A fraction of the knotted core's length when the phase started.
    Fraction(f64),
    /// Erg (g·cm²/s²).
    Erg(f64),
}

impl Threshold {
    /// The unit's name as written in a scenario (`Cm`, `L`, `D`, `Fraction`, `Erg`).
    pub fn unit(self) -> &'static str {
        match self {
            Threshold::Cm(_) => "Cm",
            Threshold::L(_) => "L",
            Threshold::D(_) => "D",
            Threshold::Fraction(_) => "Fraction",
            Threshold::Erg(_) => "Erg",
        }
    }

    /// The number, in its unit.
    pub fn value(self) -> f64 {
        match self {
            Threshold::Cm(v)
            | Threshold::L(v)
            | Threshold::D(v)
            | Threshold::Fraction(v)
            | Threshold::Erg(v) => v,
        }
    }
}

impl Quantity {
    /// Whether this quantity can be compared `direction` a threshold in the unit of
    /// `threshold`: knot start in cm or L, span in cm, L or D, core start in L, core length in
    /// D, either way; core growth and shrink as a fraction, `Above` only (a growth below a
    /// fraction holds as the phase starts); kinetic energy in erg, `Below` only (settled).
    pub fn admits(self, direction: Direction, threshold: Threshold) -> bool {
        use Threshold::{Cm, D, Erg, Fraction, L};
        matches!(
            (self, direction, threshold),
            (Quantity::KnotStart, _, Cm(_) | L(_))
                | (Quantity::Span, _, Cm(_) | L(_) | D(_))
                | (Quantity::CoreStart, _, L(_))
                | (Quantity::CoreLength, _, D(_))
                | (Quantity::CoreGrowth | Quantity::CoreShrink, Direction::Above, Fraction(_))
                | (Quantity::KineticEnergy, Direction::Below, Erg(_))
        )
    }

    /// What [`Quantity::admits`], in words for an error message.
    fn admitted(self) -> &'static str {
        match self {
            Quantity::KnotStart => "Below or Above, in Cm or L",
            Quantity::Span => "Below or Above, in Cm, L or D",
            Quantity::CoreStart => "Below or Above, in L",
            Quantity::CoreLength => "Below or Above, in D",
            Quantity::CoreGrowth | Quantity::CoreShrink => "Above, as a Fraction",
            Quantity::KineticEnergy => "Below, in Erg",
        }
    }
}

/// One end condition: `(quantity, direction, threshold)`, e.g. `(Span, Below, D(12.6))`: the
/// knot's span is at most 12.6 local diameters. Only combinations a quantity admits
/// ([`Quantity::admits`]) can be made, in code ([`Condition::new`]) or from a scenario file.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "(Quantity, Direction, Threshold)", into = "(Quantity, Direction, Threshold)")]
pub struct Condition {
    quantity: Quantity,
    direction: Direction,
    threshold: Threshold,
}

impl Condition {
    /// The condition `quantity` `direction` `threshold`.
    ///
    /// # Errors
    /// [`ControlError::NotACondition`] if the quantity does not admit that direction or unit
    /// (a knot start in diameters, a kinetic energy in cm).
    pub fn new(
        quantity: Quantity,
        direction: Direction,
        threshold: Threshold,
    ) -> Result<Self, ControlError> {
        if quantity.admits(direction, threshold) {
            Ok(Self { quantity, direction, threshold })
        } else {
            Err(ControlError::NotACondition {
                quantity,
                direction,
                unit: threshold.unit(),
                admitted: quantity.admitted(),
            })
        }
    }

    /// What it looks at.
    pub fn quantity(&self) -> Quantity {
        self.quantity
    }

    /// Which side of the threshold.
    pub fn direction(&self) -> Direction {
        self.direction
    }

    /// The threshold and its unit.
    pub fn threshold(&self) -> Threshold {
        self.threshold
    }

    /// Whether it holds for what is `observed`; never without the observation it needs (no
    /// self contacts, an unknotted frame, no core when the phase started). A threshold in L
    /// is compared in cm as `fraction · L`, a growth as `now ≥ (1 + f)·start`, a shrink as
    /// `now ≤ (1 − f)·start`.
    pub fn holds(&self, observed: &Observation<'_>) -> bool {
        use Threshold::{Cm, D, Erg, Fraction, L};
        let compare = |value: f64, limit: f64| match self.direction {
            Direction::Below => value <= limit,
            Direction::Above => value >= limit,
        };
        let span = observed.span;
        let of_l = |fraction: f64| fraction * observed.body_length_cm;
        let now_and_start = observed.core_length_d.zip(observed.core_length_d_at_start);
        match (self.quantity, self.threshold) {
            (Quantity::KnotStart, Cm(cm)) => span.is_some_and(|s| compare(s.start_cm, cm)),
            (Quantity::KnotStart, L(f)) => span.is_some_and(|s| compare(s.start_cm, of_l(f))),
            (Quantity::Span, Cm(cm)) => span.is_some_and(|s| compare(s.length_cm(), cm)),
            (Quantity::Span, L(f)) => span.is_some_and(|s| compare(s.length_cm(), of_l(f))),
            (Quantity::Span, D(d)) => span.is_some_and(|s| compare(s.length_d(), d)),
            (Quantity::CoreStart, L(f)) => observed.core_start_l.is_some_and(|s| compare(s, f)),
            (Quantity::CoreLength, D(d)) => observed.core_length_d.is_some_and(|l| compare(l, d)),
            (Quantity::CoreGrowth, Fraction(f)) => {
                now_and_start.is_some_and(|(now, start)| now >= (1.0 + f) * start)
            }
            (Quantity::CoreShrink, Fraction(f)) => {
                now_and_start.is_some_and(|(now, start)| now <= (1.0 - f) * start)
            }
            (Quantity::KineticEnergy, Erg(e)) => compare(observed.kinetic_energy_erg, e),
            // Not admitted, so never made (`Condition::new`).
            _ => false,
        }
    }
}

impl TryFrom<(Quantity, Direction, Threshold)> for Condition {
    type Error = ControlError;

    /// [`Condition::new`], for reading a scenario.
    fn try_from(
        (quantity, direction, threshold): (Quantity, Direction, Threshold),
    ) -> Result<Self, ControlError> {
        Self::new(quantity, direction, threshold)
    }
}

impl From<Condition> for (Quantity, Direction, Threshold) {
    /// The tuple a scenario file writes.
    fn from(condition: Condition) -> Self {
        (condition.quantity, condition.direction, condition.threshold)
    }
}

/// End conditions of a phase: it ends once `seconds` have passed, or once any condition of
/// `when` has held without interruption for `hold_s`. The knot conditions read the self
/// contacts of the step ([`KnotSpan`]); without contacts only the duration and the other
/// conditions count.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Until {
    /// Longest duration (s).
    pub seconds: f64,
    /// How long a condition must hold without interruption before the phase ends (s,
    /// default 0: at the first step it holds). The contact span flickers by 1–2 cm between
    /// steps as contacts at the knot's ends appear and vanish at the margin; a few tenths of a
    /// second keep one flicker from ending a phase.
    #[serde(default)]
    pub hold_s: f64,
    /// The conditions, any of which ends the phase (default none: only the duration).
    #[serde(default)]
    pub when: Vec<Condition>,
}

/// What a phase's end conditions look at, at the start of a step.
#[derive(Clone, Copy, Debug)]
pub struct Observation<'a> {
    /// The knot's contact span, if there are self contacts.
    pub span: Option<&'a KnotSpan>,
    /// The body length L (cm).
    pub body_length_cm: f64,
    /// The kinetic energy (erg).
    pub kinetic_energy_erg: f64,
    /// The knotted core's head-ward end at the latest observation (fraction of L), if the
    /// body was knotted then.
    pub core_start_l: Option<f64>,
    /// The knotted core's length at the latest observation in local diameters, if the body
    /// was knotted then.
    pub core_length_d: Option<f64>,
    /// The core's length (local diameters) at the last observation before the phase started.
    pub core_length_d_at_start: Option<f64>,
}

impl Until {
    /// Whether a phase that started `elapsed` seconds ago is over at time `t` given what is
    /// `observed`: its duration has passed, or a condition has held since `since` for at
    /// least `hold_s`. Updates `since` (the phase's
    /// [`PhaseProgress::condition_since`](crate::PhaseProgress::condition_since)): set when a
    /// condition starts to hold, cleared when none holds.
    pub fn over(
        &self,
        t: f64,
        elapsed: f64,
        observed: &Observation<'_>,
        since: &mut Option<f64>,
    ) -> bool {
        let holds = self.when.iter().any(|condition| condition.holds(observed));
        *since = if holds { Some(since.unwrap_or(t)) } else { None };
        elapsed >= self.seconds || since.is_some_and(|since| t - since >= self.hold_s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Direction::{Above, Below};
    use Quantity::{CoreGrowth, CoreLength, CoreShrink, CoreStart, KnotStart, Span};
    use Threshold::{Cm, D, Fraction, L};

    fn seen(span: Option<&KnotSpan>) -> Observation<'_> {
        Observation {
            span,
            body_length_cm: 40.0,
            kinetic_energy_erg: 1.0,
            core_start_l: None,
            core_length_d: None,
            core_length_d_at_start: None,
        }
    }

    fn span(start_cm: f64, end_cm: f64) -> KnotSpan {
        KnotSpan {
            start_cm,
            end_cm,
            first_contact_cm: start_cm,
            last_contact_cm: start_cm,
            diameter_cm: 2.0,
        }
    }

    /// An [`Until`] of 5 s ending on the conditions `when`, each admitted.
    fn ending_on(when: &[(Quantity, Direction, Threshold)]) -> Until {
        let when = when.iter().map(|&c| Condition::try_from(c).expect("admitted")).collect();
        Until { seconds: 5.0, hold_s: 0.0, when }
    }

    /// Whether a condition of `until` holds for the knot at `s` on a body of `length_cm`.
    fn knot_condition(until: &Until, s: Option<&KnotSpan>, length_cm: f64) -> bool {
        let observed = Observation { body_length_cm: length_cm, ..seen(s) };
        until.when.iter().any(|c| c.holds(&observed))
    }

    #[test]
    fn until_ends_at_the_first_condition_that_holds() {
        let until = ending_on(&[(KnotStart, Below, Cm(3.0)), (Span, Below, Cm(20.0))]);
        let condition = |until: &Until, s: Option<&KnotSpan>| knot_condition(until, s, 40.0);
        assert!(!condition(&until, Some(&span(10.0, 35.0))));
        assert!(condition(&until, Some(&span(2.5, 35.0))), "knot start near the head");
        assert!(condition(&until, Some(&span(10.0, 29.5))), "span tight enough");
        assert!(!condition(&until, None), "without contacts only the duration counts");
        let loosen = ending_on(&[(KnotStart, Below, Cm(3.0)), (Span, Above, Cm(27.0))]);
        assert!(condition(&loosen, Some(&span(10.0, 37.0))));
        assert!(!condition(&loosen, Some(&span(10.0, 29.5))));
    }

    #[test]
    fn the_core_condition_looks_at_the_core_of_the_latest_recorded_frame() {
        let until = ending_on(&[(CoreStart, Below, L(0.04))]);
        let at = |core_start_l| Observation { core_start_l, ..seen(None) };
        let mut since = None;
        assert!(!until.over(1.0, 1.0, &at(Some(0.05)), &mut since), "still 0.05 L away");
        assert!(!until.over(1.1, 1.1, &at(None), &mut since), "an unknotted frame");
        assert!(until.over(1.2, 1.2, &at(Some(0.04)), &mut since), "within 0.04 L");
    }

    #[test]
    fn loosened_and_tightened_look_at_the_cores_length_in_diameters() {
        let loosen = ending_on(&[(CoreLength, Above, D(18.0))]);
        let tighten = ending_on(&[(CoreLength, Below, D(13.0))]);
        let at = |core_length_d| Observation { core_length_d, ..seen(None) };
        let over = |until: &Until, d| until.over(1.0, 1.0, &at(d), &mut None);
        assert!(!over(&loosen, Some(17.9)) && over(&loosen, Some(18.0)));
        assert!(!over(&tighten, Some(13.1)) && over(&tighten, Some(13.0)));
        assert!(!over(&loosen, None) && !over(&tighten, None), "an unknotted frame");

        // Relative to the core when the phase started: 14 D → loosened at 18.2 D (+30 %),
        // tightened at 10.5 D (−25 %).
        let grow = ending_on(&[(CoreGrowth, Above, Fraction(0.3))]);
        let shrink = ending_on(&[(CoreShrink, Above, Fraction(0.25))]);
        let from_14 = |core_length_d| Observation {
            core_length_d,
            core_length_d_at_start: Some(14.0),
            ..seen(None)
        };
        let over = |until: &Until, d| until.over(1.0, 1.0, &from_14(d), &mut None);
        assert!(!over(&grow, Some(18.1)) && over(&grow, Some(18.2)));
        assert!(!over(&shrink, Some(10.6)) && over(&shrink, Some(10.5)));
        let unknown_start = Observation { core_length_d: Some(30.0), ..seen(None) };
        assert!(!grow.over(1.0, 1.0, &unknown_start, &mut None), "no core when the phase began");
    }

    #[test]
    fn body_relative_conditions_scale_with_the_body_length() {
        let until = ending_on(&[(KnotStart, Below, L(0.05))]);
        let near = span(2.5, 20.0);
        assert!(knot_condition(&until, Some(&near), 60.0), "2.5 cm ≤ 0.05 · 60 cm");
        assert!(!knot_condition(&until, Some(&near), 40.0), "2.5 cm > 0.05 · 40 cm");
        let tight = ending_on(&[(Span, Below, L(0.5))]);
        assert!(knot_condition(&tight, Some(&span(10.0, 29.0)), 40.0));
        assert!(!knot_condition(&tight, Some(&span(10.0, 31.0)), 40.0));
    }

    #[test]
    fn a_knot_condition_ends_the_phase_only_after_holding_for_hold_s() {
        let until = Until { hold_s: 0.3, ..ending_on(&[(Span, Below, Cm(20.0))]) };
        let (tight, loose) = (span(10.0, 29.5), span(10.0, 35.0));
        let mut since = None;
        assert!(!until.over(1.0, 1.0, &seen(Some(&tight)), &mut since), "a single dip");
        assert_eq!(since, Some(1.0));
        assert!(!until.over(1.1, 1.1, &seen(Some(&loose)), &mut since), "the flicker is over");
        assert_eq!(since, None);
        for t in [1.2, 1.3, 1.4] {
            assert!(!until.over(t, t, &seen(Some(&tight)), &mut since), "held only since 1.2 s");
        }
        assert!(until.over(1.5, 1.5, &seen(Some(&tight)), &mut since), "held for 0.3 s");
        assert!(until.over(5.0, 5.0, &seen(None), &mut None), "the duration ends it regardless");
    }

    #[test]
    fn a_unit_a_quantity_cannot_be_read_in_is_refused_with_what_it_admits() {
        let refused = Condition::new(KnotStart, Below, D(3.0)).expect_err("no D for a start");
        assert_eq!(
            refused.to_string(),
            "(KnotStart, Below, D(…)) is not an end condition: KnotStart is compared Below or \
             Above, in Cm or L"
        );
        assert!(Condition::new(CoreShrink, Below, Fraction(0.2)).is_err(), "Above only");
        assert!(Condition::new(Quantity::KineticEnergy, Below, Cm(1.0)).is_err());
        let settled = Condition::new(Quantity::KineticEnergy, Below, Threshold::Erg(1e-9));
        let settled = settled.expect("admitted");
        assert!(settled.holds(&Observation { kinetic_energy_erg: 1e-9, ..seen(None) }));
        assert!(!settled.holds(&seen(None)), "1 erg is not settled");
    }
}
