//! Knot analysis of the hagfish-like 100-vertex centreline with an overhand knot (trefoil):
//! the 64-direction vote alone (the per-frame check) and with the extent search.

use criterion::{Criterion, criterion_group, criterion_main};
use hagfish_knots::{KnotOptions, analyse_knot};
use std::hint::black_box;

#[path = "../tests/integration/hagfish_curve.rs"]
mod hagfish_curve;

fn knot_type(c: &mut Criterion) {
    let (points, _) = hagfish_curve::hagfish_trefoil();
    for (name, directions, extent) in [
        ("vote_50_directions", 50, false),
        ("vote_64_directions", 64, false),
        ("vote_64_with_extent", 64, true),
    ] {
        let options = KnotOptions { directions, extent, ..KnotOptions::default() };
        c.bench_function(name, |b| b.iter(|| analyse_knot(black_box(&points), &options)));
    }
}

criterion_group!(benches, knot_type);
criterion_main!(benches);
