//! Every check of `docs/validation.md` within its tolerance (run in `--release`).

use std::path::Path;

use hagfish_validation::{Check, all_checks, cantilever, tension};

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn assert_passes(check: &Check) {
    assert!(
        check.passes(),
        "{}: measured {} vs expected {} ({}): error {:.3e} > {:.0e}",
        check.name,
        check.measured,
        check.expected,
        check.formula,
        check.error(),
        check.tolerance
    );
}

#[test]
fn a_small_tip_load_deflects_the_cantilever_by_pl3_over_3b() {
    let [deflection, moment] = cantilever::small_load(root(), 100).expect("runs");
    assert_passes(&deflection);
    assert_passes(&moment);
}

#[test]
fn the_cantilever_error_falls_with_the_number_of_bodies() {
    let errors: Vec<f64> = [20, 50]
        .iter()
        .map(|&n| cantilever::small_load(root(), n).expect("runs")[0].error())
        .collect();
    let fine = cantilever::small_load(root(), 100).expect("runs")[0].error();
    assert!(errors[0] > errors[1] && errors[1] > fine, "errors {errors:?} then {fine}");
}

#[test]
fn a_large_tip_load_bends_the_cantilever_into_the_elastica() {
    assert_passes(&cantilever::large_load(root(), 3.0).expect("runs"));
}

#[test]
fn a_straight_rod_pulled_at_the_tail_carries_the_pull_at_every_joint() {
    assert_passes(&tension::axial(root()).expect("runs"));
}

#[test]
fn the_table_has_every_check() {
    let checks = all_checks(root()).expect("runs");
    assert!(checks.len() >= 8, "{} checks", checks.len());
}
