//! Where the knot sits along the body, read off the self contacts: the knot region runs from
//! the most anterior contact point to the most posterior one. Arc lengths are measured from
//! the head along the centreline (cm); a knot size is also given in mean local diameters D.

use hagfish_geometry::{Centreline, SelfContact};

/// The stretch of body the self contacts span.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct KnotSpan {
    /// Arc length of the most anterior contact point, min u_a (cm).
    pub start_cm: f64,
    /// Arc length of the most posterior contact point, max u_b (cm).
    pub end_cm: f64,
    /// Arc length of the first contact's anterior point (cm).
    pub first_contact_cm: f64,
    /// Arc length of the last contact's anterior point (cm).
    pub last_contact_cm: f64,
    /// The mean local diameter over the stretch, 2 r̄ (cm): its unit for a knot size that
    /// carries over to thicker or thinner bodies ([`KnotSpan::length_d`]).
    pub diameter_cm: f64,
}

/// Radii averaged for [`KnotSpan::diameter_cm`]: the midpoints of this many equal parts of
/// the stretch's spline parameters.
const DIAMETER_SAMPLES: usize = 8;

impl KnotSpan {
    /// The span of `contacts` (sorted by u_a), or `None` without contacts.
    pub fn of(contacts: &[SelfContact], centreline: &Centreline) -> Option<Self> {
        let first = contacts.first()?;
        let last = contacts.last()?;
        let end = contacts.iter().map(|c| c.u_b).fold(f64::NEG_INFINITY, f64::max);
        let part = (end - first.u_a) / DIAMETER_SAMPLES as f64;
        let radii: f64 = (0..DIAMETER_SAMPLES)
            .map(|k| centreline.radius(first.u_a + (k as f64 + 0.5) * part))
            .sum();
        Some(Self {
            start_cm: centreline.arc_length(first.u_a),
            end_cm: centreline.arc_length(end),
            first_contact_cm: centreline.arc_length(first.u_a),
            last_contact_cm: centreline.arc_length(last.u_a),
            diameter_cm: 2.0 * radii / DIAMETER_SAMPLES as f64,
        })
    }

    /// Length of the knotted stretch in mean local diameters, `(end − start) / D`: the knot's
    /// size relative to the body's thickness (the thesis' 21 cm is 12.6 D where ES103's tied knot
    /// sits).
    pub fn length_d(&self) -> f64 {
        self.length_cm() / self.diameter_cm
    }

    /// Length of the knotted stretch, `end − start` (cm).
    pub fn length_cm(&self) -> f64 {
        self.end_cm - self.start_cm
    }

    /// Midpoint of the knotted stretch (cm from the head): the knot's position.
    pub fn midpoint_cm(&self) -> f64 {
        0.5 * (self.start_cm + self.end_cm)
    }
}
