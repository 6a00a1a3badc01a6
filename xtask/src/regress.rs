//! `cargo xtask regress`: runs every scenario of `data/scenarios` in release through the
//! `hagfish_sim` library (in parallel threads, at most one per core), computes its metrics
//! (`metrics.rs`) and either compares them with `data/regress/<scenario>.ron` under the
//! tolerances of `tolerance.rs` (check) or rewrites those goldens (bless).

use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use hagfish_run::RunOptions;
use hagfish_scenario::LoadedScenario;

use crate::golden::{Golden, Platform};
use crate::metrics::{Samples, Value, metrics};
use crate::table::{self, Row};
use crate::tolerance::{PERTURBATIONS, Tolerance, spread, tolerance};

/// Compare with the goldens, or rewrite them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Compare and fail on a difference.
    Check,
    /// Rewrite the goldens.
    Bless,
}

/// The command that rewrites every golden.
const BLESS_COMMAND: &str = "cargo xtask regress --bless";

/// Runs the regression in `root` (the workspace); `only` limits it to the named scenarios.
/// Returns whether everything passed (always true after a bless).
pub fn run(root: &Path, mode: Mode, only: &[String]) -> Result<bool, String> {
    let scenarios = scenario_names(&root.join("data/scenarios"))?;
    if let Some(unknown) = only.iter().find(|name| !scenarios.contains(name)) {
        return Err(format!("no scenario data/scenarios/{unknown}.ron"));
    }
    let selected: Vec<String> =
        scenarios.into_iter().filter(|s| only.is_empty() || only.contains(s)).collect();
    let goldens = root.join("data/regress");
    let directory = root.join("data/scenarios");
    let platform = Platform::current();
    match mode {
        Mode::Bless => {
            let results = run_scenarios(&directory, &selected, &PERTURBATIONS)?;
            std::fs::create_dir_all(&goldens).map_err(|e| format!("{}: {e}", goldens.display()))?;
            for (name, runs) in results {
                let (written, perturbed) = runs.split_first().ok_or("no run")?;
                let spreads = written
                    .iter()
                    .map(|(metric, value)| {
                        let others: Vec<Value> =
                            perturbed.iter().filter_map(|run| find(run, metric)).collect();
                        spread(metric, value, &others)
                            .map(|s| (metric.clone(), s))
                            .map_err(|e| format!("{name}: the behaviour depends on rounding: {e}"))
                    })
                    .collect::<Result<Vec<_>, String>>()?;
                let path = goldens.join(format!("{name}.ron"));
                let golden =
                    Golden { platform: platform.clone(), metrics: written.clone(), spreads };
                golden.write(&name, &path)?;
                println!("blessed {}", path.display());
            }
            Ok(true)
        }
        Mode::Check => {
            let results = run_scenarios(&directory, &selected, &[])?;
            let mut rows = Vec::new();
            for (name, runs) in results {
                let golden = Golden::read(&goldens.join(format!("{name}.ron")))?;
                rows.extend(compare(&name, golden.as_ref(), &runs[0], &platform));
            }
            table::print(&rows);
            let passed = rows.iter().all(|r| r.ok != Some(false));
            if passed {
                println!("regress: all {} checks passed", rows.len());
            } else {
                let failed = rows.iter().filter(|r| r.ok == Some(false)).count();
                println!("regress: {failed} of {} checks FAILED", rows.len());
                println!("if the change is intended, rewrite the goldens with: {BLESS_COMMAND}");
            }
            Ok(passed)
        }
    }
}

/// The value of metric `name` in `list`.
fn find(list: &[(String, Value)], name: &str) -> Option<Value> {
    list.iter().find(|(n, _)| n == name).map(|(_, v)| v.clone())
}

/// Stems of the `.ron` files in `directory`, sorted.
fn scenario_names(directory: &Path) -> Result<Vec<String>, String> {
    let entries =
        std::fs::read_dir(directory).map_err(|e| format!("{}: {e}", directory.display()))?;
    let mut names: Vec<String> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .filter_map(|p| p.file_stem().and_then(|s| s.to_str()).map(str::to_owned))
        .collect();
    names.sort();
    Ok(names)
}

/// The metrics of one scenario, `(metric, value)` in table order.
type Metrics = Vec<(String, Value)>;

/// Runs the named scenarios as written and then with their time step scaled by
/// `1 + perturbation` for each of `perturbations`, on at most one thread per core; per
/// scenario, in the given order, the metrics of the run as written and then of each perturbed
/// run.
fn run_scenarios(
    directory: &Path,
    names: &[String],
    perturbations: &[f64],
) -> Result<Vec<(String, Vec<Metrics>)>, String> {
    let variants: Vec<f64> = std::iter::once(0.0).chain(perturbations.iter().copied()).collect();
    let jobs: Vec<(&String, f64)> =
        names.iter().flat_map(|n| variants.iter().map(move |&p| (n, p))).collect();
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<Metrics, String>>>> = Mutex::new(vec![None; jobs.len()]);
    std::thread::scope(|scope| {
        for _ in 0..cores.min(jobs.len()) {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&(name, perturbation)) = jobs.get(i) else { break };
                    let result = run_one(&directory.join(format!("{name}.ron")), perturbation);
                    if let Ok(mut all) = results.lock() {
                        all[i] = Some(result);
                    }
                }
            });
        }
    });
    let results = results.into_inner().map_err(|_| "a scenario thread panicked".to_owned())?;
    let mut results = results.into_iter();
    names
        .iter()
        .map(|name| {
            let runs = results
                .by_ref()
                .take(variants.len())
                .map(|r| r.unwrap_or_else(|| Err("not run".into())))
                .collect::<Result<Vec<Metrics>, String>>()
                .map_err(|e| format!("{name}: {e}"))?;
            Ok((name.clone(), runs))
        })
        .collect()
}

/// Runs one scenario file with its time step scaled by `1 + perturbation` and computes its
/// metrics.
fn run_one(path: &Path, perturbation: f64) -> Result<Metrics, String> {
    let start = Instant::now();
    let mut loaded = LoadedScenario::load(path).map_err(|e| e.to_string())?;
    loaded.scenario.time_step_s *= 1.0 + perturbation;
    let mut samples = Samples::default();
    let outcome = hagfish_run::run(&loaded, RunOptions::default(), &mut samples, &mut |_| {})
        .map_err(|e| e.to_string())?;
    let end = outcome.state.clone();
    let summary = outcome.finished().map_err(|e| e.to_string())?;
    eprintln!(
        "ran {} (δh/h = {perturbation:e}, {} steps) in {:.1} s",
        path.display(),
        summary.steps,
        start.elapsed().as_secs_f64()
    );
    Ok(metrics(&samples, &summary, &end))
}

/// The table rows of one scenario: every metric of the run and of the golden.
fn compare(
    scenario: &str,
    golden: Option<&Golden>,
    now: &[(String, Value)],
    platform: &Platform,
) -> Vec<Row> {
    let Some(golden) = golden else {
        return vec![Row {
            scenario: scenario.to_owned(),
            metric: "(golden)".into(),
            golden: None,
            now: None,
            tolerance: format!("missing data/regress/{scenario}.ron"),
            ok: Some(false),
        }];
    };
    let same_platform = golden.platform == *platform;
    let mut names: Vec<&str> = now.iter().map(|(n, _)| n.as_str()).collect();
    for (name, _) in &golden.metrics {
        if !names.contains(&name.as_str()) {
            names.push(name);
        }
    }
    names
        .into_iter()
        .map(|name| {
            let (g, n) = (find(&golden.metrics, name), find(now, name));
            let rule = tolerance(name, g.as_ref().unwrap_or(&Value::Missing), golden.spread(name));
            let ok = match (&g, &n) {
                (Some(g), Some(n)) => rule.accepts(g, n, same_platform),
                _ => Some(false),
            };
            let tolerance = match (rule, same_platform) {
                (Tolerance::Digest, false) => format!("blessed on {}", golden.platform.target),
                _ => rule.describe(),
            };
            Row {
                scenario: scenario.to_owned(),
                metric: name.to_owned(),
                golden: g,
                now: n,
                tolerance,
                ok,
            }
        })
        .collect()
}
