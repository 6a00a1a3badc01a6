//! Broad phase and whole self-contact detection at 100 bodies on tangled centrelines, and the
//! broad phase of a straight 10 000-body chain (no pairs: what a long free chain pays).

#![allow(missing_docs)]

#[path = "../tests/integration/curves.rs"]
mod curves;

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use curves::{BODY_COUNT, BODY_LENGTH, hagfish_radii, helix, tangle};
use hagfish_geometry::{
    BroadPhase, BroadPhaseOptions, Centreline, ContactDetector, DetectorOptions, closest_points,
};

fn bench(c: &mut Criterion) {
    let radii = hagfish_radii(BODY_COUNT);
    let lengths = vec![BODY_LENGTH; BODY_COUNT];
    for (name, centres) in [("tangle", tangle(BODY_COUNT, 1)), ("helix", helix(BODY_COUNT))] {
        let line = Centreline::new(&centres, &radii).expect("valid centreline");
        let mut broad = BroadPhase::new(BroadPhaseOptions::default()).expect("valid options");
        let mut pairs = Vec::new();
        c.bench_function(&format!("broad_phase/{name}/100"), |b| {
            b.iter(|| {
                broad.find_pairs(black_box(&line), &lengths, &mut pairs).expect("valid lengths");
            })
        });
        let mut detector = ContactDetector::new(DetectorOptions::default()).expect("valid");
        let mut contacts = Vec::new();
        c.bench_function(&format!("detect/{name}/100"), |b| {
            b.iter(|| {
                detector.detect(black_box(&line), &lengths, &mut contacts).expect("valid lengths")
            })
        });
        let mut centreline = line.clone();
        c.bench_function(&format!("centreline_update/{name}/100"), |b| {
            b.iter(|| centreline.update(black_box(&centres), &radii).expect("valid centreline"))
        });
    }
    let long = 10_000;
    let straight: Vec<_> =
        (0..long).map(|k| glam::DVec3::new(BODY_LENGTH * k as f64, 0.0, 0.0)).collect();
    let line = Centreline::new(&straight, &vec![0.89; long]).expect("valid centreline");
    let (mut broad, mut pairs) =
        (BroadPhase::new(BroadPhaseOptions::default()).expect("valid"), Vec::new());
    c.bench_function("broad_phase/straight/10000", |b| {
        b.iter(|| broad.find_pairs(black_box(&line), &vec![BODY_LENGTH; long], &mut pairs))
    });
    let line = Centreline::new(&tangle(BODY_COUNT, 1), &radii).expect("valid centreline");
    let (a, b) = (line.segment(20), line.segment(60));
    c.bench_function("closest_points/tangle", |bench| {
        bench.iter(|| closest_points(black_box(&a), black_box(&b)))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
