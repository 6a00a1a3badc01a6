//! `cargo xtask regress`: runs every scenario of `data/scenarios` in release through the
//! `hagfish_sim` library (in parallel threads, at most one per core), computes its metrics
//! (`metrics.rs`) and either compares them with `data/regress/<scenario>.ron` under the
//! tolerances of `tolerance.rs` (check) or rewrites those goldens (bless).

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use hagfish_sim::{LoadedScenario, RunOptions};

use crate::golden::{Golden, Platform};
use crate::metrics::{Samples, Value, metrics};
use crate::table::{self, Row};
use crate::tolerance::{Tolerance, tolerance};

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
    let results = run_scenarios(&root.join("data/scenarios"), &selected)?;
    let platform = Platform::current();
    match mode {
        Mode::Bless => {
            std::fs::create_dir_all(&goldens).map_err(|e| format!("{}: {e}", goldens.display()))?;
            for (name, values) in results {
                let path = goldens.join(format!("{name}.ron"));
                Golden { platform: platform.clone(), metrics: values }.write(&name, &path)?;
                println!("blessed {}", path.display());
            }
            Ok(true)
        }
        Mode::Check => {
            let mut rows = Vec::new();
            for (name, values) in results {
                let golden = Golden::read(&goldens.join(format!("{name}.ron")))?;
                rows.extend(compare(&name, golden.as_ref(), &values, &platform));
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

/// Runs the named scenarios on at most one thread per core; results in the given order.
fn run_scenarios(directory: &Path, names: &[String]) -> Result<Vec<(String, Metrics)>, String> {
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<Metrics, String>>>> = Mutex::new(vec![None; names.len()]);
    std::thread::scope(|scope| {
        for _ in 0..cores.min(names.len()) {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(name) = names.get(i) else { break };
                    let result = run_one(&directory.join(format!("{name}.ron")));
                    if let Ok(mut all) = results.lock() {
                        all[i] = Some(result);
                    }
                }
            });
        }
    });
    let results = results.into_inner().map_err(|_| "a scenario thread panicked".to_owned())?;
    names
        .iter()
        .zip(results)
        .map(|(name, result)| {
            let values = result.unwrap_or_else(|| Err("not run".into()));
            values.map(|v| (name.clone(), v)).map_err(|e| format!("{name}: {e}"))
        })
        .collect()
}

/// Runs one scenario file and computes its metrics.
fn run_one(path: &PathBuf) -> Result<Metrics, String> {
    let start = Instant::now();
    let loaded = LoadedScenario::load(path).map_err(|e| e.to_string())?;
    let mut samples = Samples::default();
    let outcome = hagfish_sim::run(&loaded, RunOptions::default(), &mut samples, &mut |_| {})
        .map_err(|e| e.to_string())?;
    let end = outcome.state.clone();
    let summary = outcome.finished().map_err(|e| e.to_string())?;
    eprintln!(
        "ran {} ({} steps) in {:.1} s",
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
    let find = |list: &[(String, Value)], name: &str| {
        list.iter().find(|(n, _)| n == name).map(|(_, v)| v.clone())
    };
    names
        .into_iter()
        .map(|name| {
            let (g, n) = (find(&golden.metrics, name), find(now, name));
            let rule = tolerance(name);
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
