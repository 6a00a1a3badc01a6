//! Loosening and tightening as the thigmotaxic targets' doing (`data/scenarios/loosen_tighten.ron`):
//! after the tie, the first contact's strands fed into the knot (and the tail end fed on
//! through it at the last contact) grow its core by ≥ 25 %, drawn out of it they shrink it by
//! ≥ 25 %, each ≥ 20 percentage points more than the control run with the same phases and
//! that phase's targets, head and tail, at zero. On ES103 as written and with the time step
//! changed by 1 to 15 parts in 10¹² (the phases amplify rounding, so the claim is checked on
//! each of these sixteen trajectories; with the tighten asked for 30 % instead of 28 %, 2 of
//! them failed). Over 48 the trefoil holds in all; the tighten reaches 24 % instead of 25 % in
//! one (δh/h = 39e-12) — docs/physics.md, which has those rates. And on a body 35 cm long,
//! on eight of these trajectories, of which two may lose the knot while tightening. A tighten
//! control whose loosened knot comes undone during that phase counts as not tightened.

use crate::common::{es103_with, fresh_dir, run_scenario};
use hagfish_bench_support::length_edits;
use hagfish_report::LoosenTighten;

/// Runs `loosen_tighten.ron` into a fresh directory `name` with `--set` values `sets`.
fn sizes(name: &str, sets: &[String]) -> LoosenTighten {
    let dir = run_scenario(name, "data/scenarios/loosen_tighten.ron", sets);
    LoosenTighten::read(&dir, "3_1").unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Runs `loosen_tighten.ron` with `sets` for δh/h = k·1e-12, k in `perturbations`, with
/// both controls, and asserts every bound on each, except on at most `may_lose` runs whose
/// knot comes undone while tightening; `name` labels the runs.
fn check_loosen_and_tighten(
    name: &str,
    sets: &[String],
    perturbations: std::ops::Range<u32>,
    may_lose: usize,
) {
    let zero = |phase: usize| {
        ["head", "tail"]
            .map(|end| format!("phases[{phase}].Thigmotaxis.parameters.{end}=(0.0, 0.0)"))
    };
    let jobs: Vec<(u32, Option<usize>)> =
        perturbations.clone().flat_map(|k| [(k, None), (k, Some(1)), (k, Some(2))]).collect();
    let next = std::sync::Mutex::new(jobs.iter());
    let results = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..2 {
            scope.spawn(|| {
                loop {
                    // A statement of its own: the queue's lock is released before the run.
                    let job = next.lock().expect("the queue").next().copied();
                    let Some((k, control)) = job else { break };
                    let h = 0.01 * (1.0 + f64::from(k) * 1e-12);
                    let mut all = sets.to_vec();
                    all.push(format!("time_step_s={h:?}"));
                    all.extend(control.into_iter().flat_map(zero));
                    let run = format!("{name}_{k}_{}", control.map_or(0, |p| p));
                    let measured = sizes(&run, &all);
                    results.lock().expect("the results").push((k, control, measured));
                }
            });
        }
    });
    let results = results.into_inner().expect("the results");
    let find = |k, control| {
        results.iter().find(|(j, c, _)| *j == k && *c == control).map(|(_, _, s)| s).expect("run")
    };
    let mut lost = Vec::new();
    for k in perturbations {
        let (run, loosen_control, tighten_control) =
            (find(k, None), find(k, Some(1)), find(k, Some(2)));
        if run.lost_in.as_deref() == Some("tighten") {
            lost.push(k);
            continue;
        }
        let label = format!("{name}, δh/h = {k}e-12");
        let failures = run.failures(loosen_control, tighten_control);
        assert!(failures.is_empty(), "{label}: {}", failures.join("; "));
    }
    assert!(
        lost.len() <= may_lose,
        "{name}: the knot came undone tightening at δh/h = {lost:?}e-12"
    );
}

#[test]
fn loosen_and_tighten_change_the_core_because_of_their_targets() {
    check_loosen_and_tighten("knot_size", &[], 0..16, 0);
}

/// The same on a body 35 cm long (mass ∝ length: 21.4 local diameters instead of 26), as
/// written and with δh/h = 1…7e-12: the tie's `min_tail_d` puts the crossover at ≈ 0.15 L
/// and the loosen's tail feed keeps the tail end beyond the knot (without the feed the
/// trefoil was lost while tightening in 6 of 16 perturbations). With it the knot still comes
/// undone while tightening on 2 of 16 (δh/h = 0…15e-12, before decision 0031 and after it
/// alike; docs/physics.md), so 2 of the 8 may; every run that keeps it meets every bound.
#[test]
fn loosen_and_tighten_carry_over_to_a_shorter_body() {
    let dir = fresh_dir("knot_size_short_body");
    let body = es103_with(&dir, "length_35", &length_edits(35.0));
    check_loosen_and_tighten(
        "knot_size_35",
        &[format!("body={:?}", body.display().to_string())],
        0..8,
        2,
    );
}
