//! Self-contact detection on tangled centrelines against dense sampling.
//!
//! Every pair of sample points of the tube (10 per segment) that are more than
//! `index_gap + 1` apart in u and closer than r(u_a) + r(u_b) must be covered by a
//! contact record. A touching sample pair lies on a segment pair whose closest points are
//! within 1 of it in each parameter, and that record is either kept or merged into a kept
//! record within the cluster radius, so "covered" means a record within
//! cluster_radius + 1 in both parameters.

use crate::curves::{BODY_COUNT, BODY_LENGTH, hagfish_radii, helix, tangle};
use glam::DVec3;
use hagfish_geometry::{Centreline, ContactDetector, DetectorOptions, SelfContact};

const SAMPLES_PER_SEGMENT: usize = 10;

/// Detects the contacts of `centres`, checks every record and the coverage of all
/// touching sample pairs; returns the number of records.
fn check_curve(name: &str, centres: &[DVec3]) -> usize {
    let radii = hagfish_radii(centres.len());
    let lengths = vec![BODY_LENGTH; centres.len()];
    let line = Centreline::new(centres, &radii).expect("valid centreline");
    let options = DetectorOptions::default();
    let mut detector = ContactDetector::new(options).expect("valid options");
    let mut contacts = Vec::new();
    let report = detector.detect(&line, &lengths, &mut contacts).expect("valid body lengths");
    check_records(&line, &options, &contacts);

    let mut again = Vec::new();
    detector.detect(&line, &lengths, &mut again).expect("valid body lengths");
    assert_eq!(contacts, again, "{name}: detection must be deterministic");

    let samples: Vec<(f64, DVec3, f64)> = (0..=line.segment_count() * SAMPLES_PER_SEGMENT)
        .map(|i| {
            let u = i as f64 / SAMPLES_PER_SEGMENT as f64;
            (u, line.point(u), line.radius(u))
        })
        .collect();
    let allowed = options.cluster_radius + 1.0;
    let (mut touching, mut worst) = (0, 0.0_f64);
    for (i, &(u_a, x_a, r_a)) in samples.iter().enumerate() {
        for &(u_b, x_b, r_b) in &samples[i + 1..] {
            if u_b - u_a <= options.index_gap as f64 + 1.0 || x_a.distance(x_b) >= r_a + r_b {
                continue;
            }
            touching += 1;
            let nearest = contacts
                .iter()
                .map(|c| (c.u_a - u_a).abs().max((c.u_b - u_b).abs()))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest <= allowed,
                "{name}: touching samples at u = ({u_a}, {u_b}) have no record within \
                 {allowed} (nearest {nearest})"
            );
            worst = worst.max(nearest);
        }
    }
    println!(
        "{name}: {report:?}; {touching} touching sample pairs, farthest from its record {worst:.3}"
    );
    assert!(touching > 0, "{name}: the test curve must touch itself");
    contacts.len()
}

/// Invariants every record and the record list must satisfy.
fn check_records(line: &Centreline, options: &DetectorOptions, contacts: &[SelfContact]) {
    for c in contacts {
        assert!(c.u_b - c.u_a > options.index_gap as f64, "{c:?}");
        assert!(c.gap < options.margin, "{c:?}");
        assert!(line.point(c.u_a).distance(c.point_a) < 1e-12);
        assert!(line.point(c.u_b).distance(c.point_b) < 1e-12);
        assert!((c.point_a.distance(c.point_b) - c.distance).abs() < 1e-12);
        assert!((c.point_a + c.distance * c.normal).distance(c.point_b) < 1e-9);
        let radii = line.radius(c.u_a) + line.radius(c.u_b);
        assert!((c.gap - (c.distance - radii)).abs() < 1e-12);
        for (t, u) in [(c.tangent_a, c.u_a), (c.tangent_b, c.u_b)] {
            assert!((t.length() - 1.0).abs() < 1e-12 && t.dot(line.tangent(u)) > 0.0);
        }
        for (w, x) in [(c.weights_a, c.point_a), (c.weights_b, c.point_b)] {
            let blend: DVec3 = w.iter().map(|(b, w)| w * line.centres()[b]).sum();
            assert!(blend.distance(x) < 1e-12);
        }
    }
    for pair in contacts.windows(2) {
        assert!((pair[0].u_a, pair[0].u_b) <= (pair[1].u_a, pair[1].u_b), "sorted by u_a");
    }
    for (i, x) in contacts.iter().enumerate() {
        for y in &contacts[i + 1..] {
            let apart = (x.u_a - y.u_a).abs().max((x.u_b - y.u_b).abs());
            assert!(apart > options.cluster_radius, "duplicates {x:?} {y:?}");
        }
    }
}

#[test]
fn helix_line_contacts_are_all_covered() {
    assert!(check_curve("helix", &helix(BODY_COUNT)) > 0);
}

#[test]
fn random_tangles_have_no_missed_contacts() {
    for seed in 1..=8 {
        assert!(check_curve(&format!("tangle {seed}"), &tangle(BODY_COUNT, seed)) > 0);
    }
}
