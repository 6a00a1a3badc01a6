//! The knotted core of a frame in body-relative units: the shortest sub-arc of the body
//! centres whose closure still has the frame's knot type (`hagfish_knots`' extent), as arc
//! lengths (cm), fractions of the body length L and a length in local diameters D — the
//! units in which knots of different bodies compare (a trefoil needs ≈ 16 D of
//! tube tied ideally).

use glam::DVec3;
use hagfish_knots::KnotReport;

/// Where the knotted core lies along the body and how long it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KnotCore {
    /// Arc length from the head body's centre to the core's head-ward end (cm), along the
    /// body centres (as every `*_cm` column of `metrics.csv`).
    pub start_cm: f64,
    /// Arc length to the core's tail-ward end (cm).
    pub end_cm: f64,
    /// The body length L (cm): the fractions below are these arc lengths over L.
    pub body_length_cm: f64,
    /// The mean diameter 2r of the core's bodies (cm).
    pub local_diameter_cm: f64,
}

impl KnotCore {
    /// The core of `knot` on the body with centres `centres` and radii `radii`, or `None`
    /// when the knot analysis found no knotted stretch (unknot, failed analysis).
    pub fn of(
        knot: &KnotReport,
        centres: &[DVec3],
        radii: &[f64],
        body_length_cm: f64,
    ) -> Option<Self> {
        let (first, last) = knot.extent?;
        if first > last || last >= centres.len() || radii.len() != centres.len() {
            return None;
        }
        // From +0 (an empty `Sum` of floats is −0, written "-0.000" for a core at the head).
        let arc = |k: usize| centres[..=k].windows(2).fold(0.0, |s, w| s + w[0].distance(w[1]));
        let core = &radii[first..=last];
        Some(Self {
            start_cm: arc(first),
            end_cm: arc(last),
            body_length_cm,
            local_diameter_cm: 2.0 * core.iter().sum::<f64>() / core.len() as f64,
        })
    }

    /// Length of the core along the body (cm).
    pub fn length_cm(&self) -> f64 {
        self.end_cm - self.start_cm
    }

    /// Arc length of the core's midpoint (cm).
    pub fn midpoint_cm(&self) -> f64 {
        0.5 * (self.start_cm + self.end_cm)
    }

    /// A length (cm) as a fraction of the body length L.
    pub fn of_body_length(&self, cm: f64) -> f64 {
        cm / self.body_length_cm
    }

    /// The core's length in local diameters, `length / D`.
    pub fn length_in_diameters(&self) -> f64 {
        self.length_cm() / self.local_diameter_cm
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hagfish_knots::{KnotAnalyser, KnotOptions};

    #[test]
    fn a_straight_body_with_a_given_extent_measures_along_its_centres() {
        let centres: Vec<DVec3> = (0..11).map(|k| DVec3::new(0.5 * k as f64, 0.0, 0.0)).collect();
        let radii = vec![0.25; 11];
        // The analysis of a straight line is the unknot: no core.
        let straight = KnotAnalyser::default()
            .analyse(&centres, &KnotOptions::default())
            .expect("a straight line is analysed");
        assert!(KnotCore::of(&straight, &centres, &radii, 5.5).is_none());
        let knotted = KnotReport { extent: Some((2, 8)), ..straight };
        let core = KnotCore::of(&knotted, &centres, &radii, 5.5).expect("a core");
        assert_eq!((core.start_cm, core.end_cm), (1.0, 4.0));
        assert_eq!(core.length_cm(), 3.0);
        assert_eq!(core.midpoint_cm(), 2.5);
        assert_eq!(core.of_body_length(core.midpoint_cm()), 2.5 / 5.5);
        assert_eq!(core.length_in_diameters(), 6.0);
        let at_head = KnotReport { extent: Some((0, 8)), ..knotted.clone() };
        let core = KnotCore::of(&at_head, &centres, &radii, 5.5).expect("a core");
        assert_eq!(format!("{:.3}", core.start_cm), "0.000");
        let outside = KnotReport { extent: Some((2, 11)), ..knotted };
        assert!(KnotCore::of(&outside, &centres, &radii, 5.5).is_none());
    }
}
