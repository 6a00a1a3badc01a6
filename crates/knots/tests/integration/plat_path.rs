//! The path a Miller Institute knot (6₂) tie would have to take (`docs/physics.md`, "Tying by
//! control"): the alternating 4-plat σ₂³σ₁⁻¹σ₂² (caps joining strands 1–2 and 3–4 at both
//! ends), cut open on its straight strand 4, is 6₂; traced from one cut end (the head), the
//! body passes six crossing sites without crossing itself, and the tail then passes them in
//! the order 2, 1, 6, 3, 4, 5, alternately over and under.

use glam::{DVec2, DVec3};
use hagfish_knots::{KnotOptions, KnotType, analyse_knot};

use crate::hagfish_curve::{polyline_length, resample};

/// A strand's height where it crosses, and where the crossings' corners are.
const HEIGHT: f64 = 0.5;
/// How far the two cut ends reach below the plat (away from it).
const END_DEPTH: f64 = 12.0;

/// The 4-plat of `word` (`±i`: σᵢ^±1 on strands 1–4, one per column at x = 1, 2, …) with caps
/// (1, 2) and (3, 4) at both ends, cut in the middle of strand 4 (which `word` must not
/// touch); the path starts at the cut end right of the middle. Strand k runs at y = 4 − k. At
/// σᵢ the strand going from level i to i + 1, read left to right, passes over (under for
/// σᵢ⁻¹), whichever way the path runs through it.
fn four_plat_cut_open(word: &[i32]) -> Vec<DVec3> {
    let columns = word.len() as f64;
    let right = columns + 1.0;
    let middle = right / 2.0;
    let y = |level: f64| 4.0 - level;
    let mut path = vec![
        DVec3::new(middle + 0.3, -END_DEPTH, 0.0),
        DVec3::new(middle + 0.3, y(4.0), 0.0),
        DVec3::new(right, y(4.0), 0.0),
    ];
    // Round the right cap of strands 3 and 4, then back along strand 3.
    path.push(DVec3::new(right + 0.5, y(3.5), 0.0));
    path.push(DVec3::new(right, y(3.0), 0.0));
    let (mut level, mut leftward) = (3usize, true);
    loop {
        let order: Vec<usize> =
            if leftward { (0..word.len()).rev().collect() } else { (0..word.len()).collect() };
        for column in order {
            let generator = word[column];
            let upper = generator.unsigned_abs() as usize;
            if level != upper && level != upper + 1 {
                continue;
            }
            let next = if level == upper { upper + 1 } else { upper };
            let x = column as f64 + 1.0;
            let step = if leftward { -0.5 } else { 0.5 };
            // Read left to right, this strand goes from level `from` to level `to`.
            let (from, to) = if leftward { (next, level) } else { (level, next) };
            let downward = to > from;
            let over = (generator > 0) == downward;
            let z = if over { HEIGHT } else { -HEIGHT };
            let mid = 0.5 * (y(level as f64) + y(next as f64));
            path.push(DVec3::new(x - step, y(level as f64), 0.0));
            path.push(DVec3::new(x, mid, z));
            path.push(DVec3::new(x + step, y(next as f64), 0.0));
            level = next;
        }
        let partner = [0, 2, 1, 4, 3][level];
        let (edge, outside) = if leftward { (0.0, -0.5) } else { (right, right + 0.5) };
        let mid = 0.5 * (y(level as f64) + y(partner as f64));
        path.push(DVec3::new(edge, y(level as f64), 0.0));
        path.push(DVec3::new(outside, mid, 0.0));
        path.push(DVec3::new(edge, y(partner as f64), 0.0));
        if partner == 4 {
            path.push(DVec3::new(middle - 0.3, y(4.0), 0.0));
            path.push(DVec3::new(middle - 0.3, -END_DEPTH, 0.0));
            return path;
        }
        (level, leftward) = (partner, !leftward);
    }
}

/// The 6₂ tie path, resampled every 0.02 units.
fn miller_institute_path() -> Vec<DVec3> {
    let plat = four_plat_cut_open(&[2, 2, 2, -1, 2, 2]);
    let spacing = 0.02;
    resample(&plat, spacing, (polyline_length(&plat) / spacing) as usize)
}

/// The crossings of `path` seen from above, as (position along the path, crossing index,
/// whether that strand is the upper one), in path order; crossings are numbered by their
/// first passage.
fn passages(path: &[DVec3]) -> Vec<(f64, usize, bool)> {
    let flat = |p: DVec3| DVec2::new(p.x, p.y);
    let mut crossings = Vec::new();
    for i in 0..path.len() - 1 {
        for j in i + 2..path.len() - 1 {
            let (a, b, c, d) = (flat(path[i]), flat(path[i + 1]), flat(path[j]), flat(path[j + 1]));
            let (r, s) = (b - a, d - c);
            let denominator = r.perp_dot(s);
            if denominator == 0.0 {
                continue;
            }
            let (u, v) = ((c - a).perp_dot(s) / denominator, (c - a).perp_dot(r) / denominator);
            if (0.0..1.0).contains(&u) && (0.0..1.0).contains(&v) {
                let first = path[i].lerp(path[i + 1], u).z;
                let second = path[j].lerp(path[j + 1], v).z;
                crossings.push((i as f64 + u, j as f64 + v, first > second));
            }
        }
    }
    crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut passages: Vec<(f64, usize, bool)> = crossings
        .iter()
        .enumerate()
        .flat_map(|(k, &(first, second, over))| [(first, k, over), (second, k, !over)])
        .collect();
    passages.sort_by(|a, b| a.0.total_cmp(&b.0));
    passages
}

#[test]
fn the_alternating_four_plat_cut_open_is_the_miller_institute_knot() {
    let path = miller_institute_path();
    // With the extent, so that the report has the knotted core's writhe (the handedness).
    let options = KnotOptions::default();
    let report = analyse_knot(&path, &options).expect("a valid curve");
    assert_eq!(report.knot, KnotType::Knot6_2, "{report:?}");
    assert!(report.agreement >= 0.9, "{report:?}");

    let mirror: Vec<DVec3> = path.iter().map(|p| p * DVec3::new(1.0, 1.0, -1.0)).collect();
    let mirrored = analyse_knot(&mirror, &options).expect("a valid curve");
    assert_eq!(mirrored.knot, KnotType::Knot6_2, "{mirrored:?}");
    assert!(report.right_handed().is_some(), "6₂ is chiral: {report:?}");
    assert_eq!(mirrored.right_handed(), report.right_handed().map(|r| !r), "{mirrored:?}");

    // With the σ₁ crossing made like the others, the diagram is no longer alternating and
    // the knot is another one.
    let other = four_plat_cut_open(&[2, 2, 2, 1, 2, 2]);
    let other = resample(&other, 0.02, (polyline_length(&other) / 0.02) as usize);
    let report = analyse_knot(&other, &options).expect("a valid curve");
    assert_ne!(report.knot, KnotType::Knot6_2, "{report:?}");
}

#[test]
fn the_tail_passes_the_six_sites_in_the_order_2_1_6_3_4_5_alternately_over_and_under() {
    let passages = passages(&miller_institute_path());
    assert_eq!(passages.len(), 12, "six crossings: {passages:?}");
    let (body, tail) = passages.split_at(6);
    assert!(body.iter().enumerate().all(|(k, p)| p.1 == k), "the body crosses nothing first");
    let order: Vec<usize> = tail.iter().map(|p| p.1 + 1).collect();
    assert_eq!(order, [2, 1, 6, 3, 4, 5], "{passages:?}");
    let layers: Vec<bool> = passages.iter().map(|p| p.2).collect();
    assert!(layers.windows(2).all(|w| w[0] != w[1]), "alternating: {passages:?}");
}
