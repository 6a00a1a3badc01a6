//! Loosening and tightening as the thigmotaxic targets' doing (`data/scenarios/loosen_tighten.ron`):
//! after the tie, the first contact's strands fed into the knot (and the tail end fed on
//! through it at the last contact) grow its core by ≥ 25 %, drawn out of it they shrink it by
//! ≥ 25 %, each ≥ 20 percentage points more than the control run with the same phases and
//! that phase's targets, head and tail, at zero. On ES103 as written and with the time step
//! changed by 1 to 15 parts in 10¹² (the phases amplify rounding, so the claim is checked on
//! each of these sixteen trajectories; with the tighten asked for 30 % instead of 28 %, 2 of
//! them failed). Over 48 the trefoil holds in all; the tighten reaches 24 % instead of 25 % in
//! one (δh/h = 39e-12) — docs/physics.md, which has those rates.

mod common;

use common::{ROOT, code_and_stderr, fresh_dir, metrics_table, run_hagfish};

/// What one run did: the core's length change over the loosen and the tighten phase (mean of
/// the phase's last 0.5 s against its first 0.5 s; `None` for a phase of less than 1 s: after
/// an unloosened knot the tighten phase's end condition holds at once), whether the trefoil
/// showed on every frame after tying, and the deepest self penetration (fraction of the local
/// radius).
struct Sizes {
    loosen: Option<f64>,
    tighten: Option<f64>,
    held: bool,
    penetration: f64,
}

/// Runs `loosen_tighten.ron` into a fresh directory `name` with `--set` values `sets`.
fn sizes(name: &str, sets: &[String]) -> Sizes {
    let dir = fresh_dir(name);
    let scenario = format!("{ROOT}/data/scenarios/loosen_tighten.ron");
    let out = dir.to_string_lossy();
    let mut args = vec!["run", &scenario, "--quiet", "--out", &out];
    for set in sets {
        args.extend(["--set", set]);
    }
    let output = run_hagfish(&args);
    assert!(output.status.success(), "{name}: {}", code_and_stderr(&output).1);
    let (header, rows) = metrics_table(&dir);
    let number = |row: &[String], column: &str| row[header[column]].parse::<f64>();
    let change = |phase: &str| {
        let frames: Vec<&Vec<String>> =
            rows.iter().filter(|r| r[header["phase"]] == phase).collect();
        let mean = |part: &[&Vec<String>]| {
            let lengths = part.iter().map(|r| number(r, "knot_core_length_cm").expect("knotted"));
            lengths.sum::<f64>() / part.len() as f64
        };
        (frames.len() >= 10).then(|| mean(&frames[frames.len() - 5..]) / mean(&frames[..5]) - 1.0)
    };
    let tied = rows.iter().position(|r| r[header["phase"]] != "tie").expect("tied");
    let penetration =
        rows.iter().map(|r| number(r, "max_self_penetration_rel").unwrap_or(f64::NAN));
    Sizes {
        loosen: change("loosen"),
        tighten: change("tighten"),
        held: rows[tied..].iter().all(|r| r[header["knot"]] == "3_1"),
        penetration: penetration.fold(0.0, f64::max),
    }
}

#[test]
fn loosen_and_tighten_change_the_core_because_of_their_targets() {
    let zero = |phase: usize| {
        ["head", "tail"]
            .map(|end| format!("phases[{phase}].Thigmotaxis.parameters.{end}=(0.0, 0.0)"))
    };
    let jobs: Vec<(u32, Option<usize>)> =
        (0..16).flat_map(|k| [(k, None), (k, Some(1)), (k, Some(2))]).collect();
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
                    let mut sets = vec![format!("time_step_s={h:?}")];
                    sets.extend(control.into_iter().flat_map(zero));
                    let name = format!("knot_size_{k}_{}", control.map_or(0, |p| p));
                    let measured = sizes(&name, &sets);
                    results.lock().expect("the results").push((k, control, measured));
                }
            });
        }
    });
    let results = results.into_inner().expect("the results");
    let find = |k, control| {
        results.iter().find(|(j, c, _)| *j == k && *c == control).map(|(_, _, s)| s).expect("run")
    };
    for k in 0..16 {
        let (run, loosen_control, tighten_control) =
            (find(k, None), find(k, Some(1)), find(k, Some(2)));
        let label = format!("δh/h = {k}e-12");
        let phase = |sizes: &Sizes, loosen: bool| {
            let change = if loosen { sizes.loosen } else { sizes.tighten };
            change.unwrap_or_else(|| panic!("{label}: a phase shorter than 1 s"))
        };
        let (loosen, tighten) = (phase(run, true), phase(run, false));
        let (loosen_control, tighten_control) =
            (phase(loosen_control, true), phase(tighten_control, false));
        assert!(run.held, "{label}: the trefoil was lost");
        assert!(run.penetration < 0.02, "{label}: penetration {} of r", run.penetration);
        assert!(loosen >= 0.25, "{label}: loosen changed the core by {loosen}");
        assert!(tighten <= -0.25, "{label}: tighten changed the core by {tighten}");
        assert!(
            loosen - loosen_control >= 0.2,
            "{label}: loosen {loosen} against {loosen_control} without targets"
        );
        assert!(
            tighten_control - tighten >= 0.2,
            "{label}: tighten {tighten} against {tighten_control} without targets"
        );
    }
}
