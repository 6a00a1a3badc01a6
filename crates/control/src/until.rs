//! When a phase ends: its duration, or a condition on the knot (where it sits, how large it
//! is, in cm, in body lengths L or in local diameters D) or on the body (settled), each read
//! from what the controller observes at the start of a step.

use serde::{Deserialize, Serialize};

use crate::knot_span::KnotSpan;

/// End conditions of a phase; it ends at the first that holds. The knot conditions read the
/// self contacts of the step ([`KnotSpan`]) and must hold without interruption for
/// `hold_s`; without contacts only the duration counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Until {
    /// Longest duration (s).
    pub seconds: f64,
    /// How long a knot condition must hold without interruption before the phase ends (s,
    /// default 0: at the first step it holds). The contact span flickers by 1–2 cm between
    /// steps as contacts at the knot's ends appear and vanish at the margin; a few tenths of a
    /// second keep one flicker from ending a phase.
    #[serde(default)]
    pub hold_s: f64,
    /// Ends once the knot's anterior end is this close to the head (cm of arc length).
    #[serde(default)]
    pub knot_start_below_cm: Option<f64>,
    /// Ends once the knot's anterior end is this far from the head (cm; sliding tail-ward).
    #[serde(default)]
    pub knot_start_above_cm: Option<f64>,
    /// Ends once the knot's span (contact stretch, cm) is at most this (tightening).
    #[serde(default)]
    pub span_below_cm: Option<f64>,
    /// Ends once the knot's span (contact stretch, cm) is at least this (loosening).
    #[serde(default)]
    pub span_above_cm: Option<f64>,
    /// [`Until::knot_start_below_cm`] as a fraction of the body length L (body-relative:
    /// carries over to other bodies).
    #[serde(default)]
    pub knot_start_below_l: Option<f64>,
    /// [`Until::knot_start_above_cm`] as a fraction of L.
    #[serde(default)]
    pub knot_start_above_l: Option<f64>,
    /// [`Until::span_below_cm`] as a fraction of L.
    #[serde(default)]
    pub span_below_l: Option<f64>,
    /// [`Until::span_above_cm`] as a fraction of L.
    #[serde(default)]
    pub span_above_l: Option<f64>,
    /// [`Until::span_below_cm`] in mean local diameters D over the span
    /// ([`KnotSpan::length_d`]): a knot size that carries over to bodies of other lengths
    /// and thicknesses.
    #[serde(default)]
    pub span_below_d: Option<f64>,
    /// [`Until::span_above_cm`] in mean local diameters D over the span.
    #[serde(default)]
    pub span_above_d: Option<f64>,
    /// Ends once the knotted core's head-ward end is within this fraction of L of the head:
    /// the core (shortest knotted sub-arc, `hagfish_knots`) of the latest observation, so
    /// it is looked at every `observe_every_s` of the scenario. Unlike
    /// [`Until::knot_start_below_l`] (the first self contact, which a loop of the tail end can
    /// make near the head while the knot is still far from it), this is where the knot itself
    /// is.
    #[serde(default)]
    pub core_start_below_l: Option<f64>,
    /// Ends once the knotted core (of the latest observation, as
    /// [`Until::core_start_below_l`]) is at least this many local diameters long: loosened.
    #[serde(default)]
    pub core_length_above_d: Option<f64>,
    /// Ends once the knotted core is at most this many local diameters long: tightened.
    #[serde(default)]
    pub core_length_below_d: Option<f64>,
    /// Ends once the knotted core is this fraction longer than when the phase started (0.3:
    /// 30 % longer): loosened relative to the knot the phase was given, whatever its size.
    #[serde(default)]
    pub core_growth_above: Option<f64>,
    /// Ends once the knotted core is this fraction shorter than when the phase started (0.25:
    /// a quarter shorter): tightened relative to the knot the phase was given.
    #[serde(default)]
    pub core_shrink_above: Option<f64>,
    /// Ends once the kinetic energy `½ Σ Vᵢ·IᵢVᵢ` is at most this (erg = g·cm²/s²) for
    /// `hold_s`: the body has settled.
    #[serde(default)]
    pub kinetic_energy_below_erg: Option<f64>,
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
    /// `observed`: its duration has passed, or a knot or settle condition has held since
    /// `since` for at least `hold_s`. Updates `since` (the phase's
    /// [`PhaseProgress::condition_since`](crate::PhaseProgress::condition_since)): set when a
    /// condition starts to hold, cleared when none holds.
    pub fn over(
        &self,
        t: f64,
        elapsed: f64,
        observed: &Observation<'_>,
        since: &mut Option<f64>,
    ) -> bool {
        let settled =
            self.kinetic_energy_below_erg.is_some_and(|e| observed.kinetic_energy_erg <= e);
        let core_near_head = self
            .core_start_below_l
            .zip(observed.core_start_l)
            .is_some_and(|(limit, start)| start <= limit);
        let core_length = |limit: Option<f64>, reached: fn(f64, f64) -> bool| {
            limit.zip(observed.core_length_d).is_some_and(|(limit, d)| reached(d, limit))
        };
        let now_and_start = observed.core_length_d.zip(observed.core_length_d_at_start);
        let changed = |fraction: Option<f64>, reached: fn(f64, f64, f64) -> bool| {
            fraction.zip(now_and_start).is_some_and(|(f, (now, start))| reached(now, start, f))
        };
        let loosened = core_length(self.core_length_above_d, |d, limit| d >= limit)
            || changed(self.core_growth_above, |now, start, f| now >= (1.0 + f) * start);
        let tightened = core_length(self.core_length_below_d, |d, limit| d <= limit)
            || changed(self.core_shrink_above, |now, start, f| now <= (1.0 - f) * start);
        let holds = settled
            || core_near_head
            || loosened
            || tightened
            || self.knot_condition(observed.span, observed.body_length_cm);
        *since = if holds { Some(since.unwrap_or(t)) } else { None };
        elapsed >= self.seconds || since.is_some_and(|since| t - since >= self.hold_s)
    }

    /// True once a knot condition holds for the knot at `span` on a body of length
    /// `body_length_cm` (the duration and `hold_s` are not looked at).
    fn knot_condition(&self, span: Option<&KnotSpan>, body_length_cm: f64) -> bool {
        let at_most = |limit: Option<f64>, value: Option<f64>| {
            limit.zip(value).is_some_and(|(limit, value)| value <= limit)
        };
        let at_least = |limit: Option<f64>, value: Option<f64>| {
            limit.zip(value).is_some_and(|(limit, value)| value >= limit)
        };
        let start = span.map(|s| s.start_cm);
        let length = span.map(KnotSpan::length_cm);
        let length_d = span.map(KnotSpan::length_d);
        let of_l = |limit: Option<f64>| limit.map(|fraction| fraction * body_length_cm);
        at_most(self.knot_start_below_cm, start)
            || at_least(self.knot_start_above_cm, start)
            || at_most(self.span_below_cm, length)
            || at_least(self.span_above_cm, length)
            || at_most(of_l(self.knot_start_below_l), start)
            || at_least(of_l(self.knot_start_above_l), start)
            || at_most(of_l(self.span_below_l), length)
            || at_least(of_l(self.span_above_l), length)
            || at_most(self.span_below_d, length_d)
            || at_least(self.span_above_d, length_d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn until_ends_at_the_first_condition_that_holds() {
        let until = Until {
            seconds: 5.0,
            hold_s: 0.0,
            knot_start_below_cm: Some(3.0),
            knot_start_above_cm: None,
            span_below_cm: Some(20.0),
            span_above_cm: None,
            ..Until::default()
        };
        let condition = |until: &Until, s: Option<&KnotSpan>| until.knot_condition(s, 40.0);
        assert!(!condition(&until, Some(&span(10.0, 35.0))));
        assert!(condition(&until, Some(&span(2.5, 35.0))), "knot start near the head");
        assert!(condition(&until, Some(&span(10.0, 29.5))), "span tight enough");
        assert!(!condition(&until, None), "without contacts only the duration counts");
        let loosen = Until { span_above_cm: Some(27.0), span_below_cm: None, ..until };
        assert!(condition(&loosen, Some(&span(10.0, 37.0))));
        assert!(!condition(&loosen, Some(&span(10.0, 29.5))));
    }

    #[test]
    fn the_core_condition_looks_at_the_core_of_the_latest_recorded_frame() {
        let until = Until { seconds: 5.0, core_start_below_l: Some(0.04), ..Until::default() };
        let at = |core_start_l| Observation { core_start_l, ..seen(None) };
        let mut since = None;
        assert!(!until.over(1.0, 1.0, &at(Some(0.05)), &mut since), "still 0.05 L away");
        assert!(!until.over(1.1, 1.1, &at(None), &mut since), "an unknotted frame");
        assert!(until.over(1.2, 1.2, &at(Some(0.04)), &mut since), "within 0.04 L");
    }

    #[test]
    fn loosened_and_tightened_look_at_the_cores_length_in_diameters() {
        let loosen = Until { seconds: 5.0, core_length_above_d: Some(18.0), ..Until::default() };
        let tighten = Until { seconds: 5.0, core_length_below_d: Some(13.0), ..Until::default() };
        let at = |core_length_d| Observation { core_length_d, ..seen(None) };
        let over = |until: &Until, d| until.over(1.0, 1.0, &at(d), &mut None);
        assert!(!over(&loosen, Some(17.9)) && over(&loosen, Some(18.0)));
        assert!(!over(&tighten, Some(13.1)) && over(&tighten, Some(13.0)));
        assert!(!over(&loosen, None) && !over(&tighten, None), "an unknotted frame");

        // Relative to the core when the phase started: 14 D → loosened at 18.2 D (+30 %),
        // tightened at 10.5 D (−25 %).
        let grow = Until { seconds: 5.0, core_growth_above: Some(0.3), ..Until::default() };
        let shrink = Until { seconds: 5.0, core_shrink_above: Some(0.25), ..Until::default() };
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
        let until = Until { seconds: 5.0, knot_start_below_l: Some(0.05), ..Until::default() };
        let near = span(2.5, 20.0);
        assert!(until.knot_condition(Some(&near), 60.0), "2.5 cm ≤ 0.05 · 60 cm");
        assert!(!until.knot_condition(Some(&near), 40.0), "2.5 cm > 0.05 · 40 cm");
        let tight = Until { seconds: 5.0, span_below_l: Some(0.5), ..Until::default() };
        assert!(tight.knot_condition(Some(&span(10.0, 29.0)), 40.0));
        assert!(!tight.knot_condition(Some(&span(10.0, 31.0)), 40.0));
    }

    #[test]
    fn a_knot_condition_ends_the_phase_only_after_holding_for_hold_s() {
        let until = Until {
            seconds: 5.0,
            hold_s: 0.3,
            knot_start_below_cm: None,
            knot_start_above_cm: None,
            span_below_cm: Some(20.0),
            span_above_cm: None,
            ..Until::default()
        };
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
}
