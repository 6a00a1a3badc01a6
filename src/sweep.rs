//! Parameter sweeps: many runs of one scenario with different overrides, each in its own run
//! directory under a sweep folder, so nothing is lost if the sweep stops half-way and a rerun
//! makes only the runs that are missing.
//!
//! A sweep folder holds
//! - `plan.json`: the scenario (absolute path), the swept parameter paths and every run's id,
//!   replicate index and overrides (`PATH=VALUE`, as `hagfish run --set` takes them), written
//!   by [`Plan::write`];
//! - `runs/<id>/`: one run directory per run (`docs/outputs.md`);
//! - `summary.csv`, `intervals.csv` and `plots/`: written by [`crate::sweep_summary::collect`] — one row per run,
//!   and per grid point each statistic's mean, spread and confidence interval
//!   ([`crate::sweep_summary`]).
//!
//! The grid file (`hagfish sweep plan GRID.ron`) names the scenario (relative to the grid file)
//! and the values of each parameter; the grid points are their Cartesian product (the last
//! parameter varies fastest), followed by any runs listed one by one. With `replicates: N`,
//! each grid point is run N times, replicate j with the time step h(1 + j·10⁻¹²)
//! ([`hagfish_scenario::rounding_perturbed_step`]): the knot runs are chaotic, and a
//! difference between grid points means something only beside the spread of its replicates.
//!
//! ```ron
//! Sweep(
//!     scenario: "../data/scenarios/tie.ron",
//!     grid: [
//!         ("time_step_s", ["0.005", "0.01"]),
//!         ("drag.quadratic_g_per_cm3", ["0.5", "1.0"]),
//!     ],
//!     runs: [["time_step_s=0.02", "duration_s=5"]],
//!     replicates: 8,
//! )
//! ```
//!
//! A run's id is its grid point's (zero-padded index), followed by `-j` for replicate j ≥ 1,
//! so that a sweep planned again with more replicates keeps every run it has made.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

use hagfish_scenario::{LoadedScenario, Override, rounding_perturbed_step};
use serde::{Deserialize, Serialize};

use crate::CliError;
use crate::manifest::{MANIFEST_FILE, Manifest, Status};
use crate::runner::{Existing, RunRequest, Source, run_into_directory};

/// The plan of a sweep folder.
pub const PLAN_FILE: &str = "plan.json";

/// The run directories' parent in a sweep folder.
pub const RUNS_DIRECTORY: &str = "runs";

/// A grid file (`GRID.ron`): the scenario and the values to sweep.
#[derive(Clone, Debug, Deserialize)]
#[serde(rename = "Sweep", deny_unknown_fields)]
pub struct Grid {
    /// The scenario file, relative to the grid file (or absolute).
    pub scenario: PathBuf,
    /// Each parameter's dotted path (as `hagfish params` lists it) and its values (as `--set`
    /// takes them); the runs are the Cartesian product.
    #[serde(default)]
    pub grid: Vec<(String, Vec<String>)>,
    /// Further runs, each a list of `PATH=VALUE` overrides.
    #[serde(default)]
    pub runs: Vec<Vec<String>>,
    /// Runs per grid point (1 … [`MAX_REPLICATES`]), each at its rounding perturbation.
    #[serde(default = "one")]
    pub replicates: usize,
}

/// The most replicates a grid point may have.
pub const MAX_REPLICATES: usize = 1000;

/// The default number of replicates.
fn one() -> usize {
    1
}

/// One planned run.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct PlannedRun {
    /// Its id: the run's directory name under `runs/` (its grid point's zero-padded index,
    /// then `-j` for replicate j ≥ 1).
    pub id: String,
    /// Its grid point's overrides, `PATH=VALUE`, in order.
    pub overrides: Vec<String>,
    /// Its replicate index j (0: the grid point as written).
    #[serde(default)]
    pub replicate: usize,
    /// The replicate's rounding perturbation, applied after `overrides`:
    /// `time_step_s=h(1 + j·10⁻¹²)` for j ≥ 1, nothing for j = 0.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub perturbation: Vec<String>,
}

/// The content of `plan.json`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Plan {
    /// The scenario file (absolute).
    pub scenario: PathBuf,
    /// The swept parameter paths, in the order of the grid then of first appearance.
    pub parameters: Vec<String>,
    /// The runs, grid point by grid point, replicates of a point together.
    pub runs: Vec<PlannedRun>,
}

/// How a sweep's run ended in this call.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RunResult {
    /// It had already ended (completed, diverged or tie failed) and was left alone.
    Skipped(Status),
    /// It was made (or resumed) and ended with this status.
    Ran(Status),
    /// It could not be made; the message says why.
    Failed(String),
}

impl Grid {
    /// Reads a grid file; errors name the file, line and column.
    ///
    /// # Errors
    /// [`CliError::Anatomy`] if the file cannot be read (or is not a regular file of at most
    /// [`hagfish_anatomy::MAX_DATA_FILE_BYTES`]), [`CliError::Grid`] if it is malformed.
    pub fn read(path: &Path) -> Result<Self, CliError> {
        let bytes = hagfish_anatomy::read_data_file(path)?;
        let text = std::str::from_utf8(&bytes).map_err(|e| CliError::RunDirectory {
            path: path.to_path_buf(),
            reason: format!("not UTF-8 text: {e}"),
        })?;
        ron::from_str(text.trim_start_matches('\u{feff}')).map_err(|e| CliError::Grid {
            path: path.to_path_buf(),
            line: e.span.start.line,
            column: e.span.start.col,
            message: e.code.to_string(),
        })
    }
}

impl Plan {
    /// The plan of `grid` read from `grid_path`: the scenario's path made canonical, every run's
    /// overrides parsed and applied to the scenario (so a wrong path or value is refused here,
    /// not half-way through the sweep).
    ///
    /// # Errors
    /// A [`CliError`] naming the run and the override that does not fit.
    pub fn of(grid: &Grid, grid_path: &Path) -> Result<Self, CliError> {
        let base = grid_path.parent().unwrap_or(Path::new("."));
        let given = base.join(&grid.scenario);
        let scenario = given
            .canonicalize()
            .map_err(|e| CliError::RunDirectory { path: given.clone(), reason: e.to_string() })?;
        let mut combinations: Vec<Vec<String>> = vec![Vec::new()];
        for (path, values) in &grid.grid {
            if values.is_empty() {
                return Err(CliError::Sweep(format!(
                    "{}: `{path}` has no values",
                    grid_path.display()
                )));
            }
            combinations = combinations
                .iter()
                .flat_map(|c| {
                    values.iter().map(move |v| [c.clone(), vec![format!("{path}={v}")]].concat())
                })
                .collect();
        }
        if grid.grid.is_empty() {
            combinations.clear();
        }
        combinations.extend(grid.runs.iter().cloned());
        if combinations.is_empty() {
            return Err(CliError::Sweep(format!(
                "{}: no runs (grid and runs empty)",
                grid_path.display()
            )));
        }
        Self::with_runs(scenario, combinations, grid.replicates)
    }

    /// The plan of `scenario` (absolute) with one grid point per list of overrides, each run
    /// `replicates` times, checked.
    ///
    /// # Errors
    /// A [`CliError`] naming the run and the override that does not fit, or a number of
    /// replicates outside 1 … [`MAX_REPLICATES`].
    pub fn with_runs(
        scenario: PathBuf,
        combinations: Vec<Vec<String>>,
        replicates: usize,
    ) -> Result<Self, CliError> {
        if !(1..=MAX_REPLICATES).contains(&replicates) {
            return Err(CliError::Sweep(format!(
                "replicates: {replicates}: expected 1 … {MAX_REPLICATES}"
            )));
        }
        let width = combinations.len().saturating_sub(1).to_string().len().max(4);
        let mut parameters: Vec<String> = Vec::new();
        let mut runs = Vec::with_capacity(combinations.len() * replicates);
        for (index, overrides) in combinations.into_iter().enumerate() {
            let parsed = parse_overrides(&overrides)?;
            let loaded = LoadedScenario::load_with(&scenario, &parsed).map_err(|e| {
                CliError::Sweep(format!("run {index} ({}): {e}", overrides.join(" ")))
            })?;
            for o in &parsed {
                if !parameters.contains(&o.path) {
                    parameters.push(o.path.clone());
                }
            }
            let step = loaded.scenario.time_step_s;
            runs.extend((0..replicates).map(|j| PlannedRun {
                id: match j {
                    0 => format!("{index:0width$}"),
                    j => format!("{index:0width$}-{j}"),
                },
                overrides: overrides.clone(),
                replicate: j,
                perturbation: match j {
                    0 => Vec::new(),
                    j => vec![format!("time_step_s={:?}", rounding_perturbed_step(step, j))],
                },
            }));
        }
        Ok(Self { scenario, parameters, runs })
    }

    /// Writes `plan.json` into `folder` (created if missing). A folder that already holds
    /// this plan, or one whose runs are all in this plan with the same id (the same sweep
    /// with fewer replicates), takes it; another plan is refused: its runs belong to it.
    ///
    /// # Errors
    /// [`CliError::Sweep`] for another plan there, [`CliError::RunDirectory`] if it cannot be
    /// written.
    pub fn write(&self, folder: &Path) -> Result<(), CliError> {
        let path = folder.join(PLAN_FILE);
        if path.exists() {
            let existing = Self::read(folder)?;
            if existing == *self {
                return Ok(());
            }
            if !self.extends(&existing) {
                return Err(CliError::Sweep(format!(
                    "{} holds another plan: choose another folder for this sweep",
                    path.display()
                )));
            }
        }
        std::fs::create_dir_all(folder.join(RUNS_DIRECTORY)).map_err(|e| {
            CliError::RunDirectory { path: folder.to_path_buf(), reason: e.to_string() }
        })?;
        let text = serde_json::to_string_pretty(self)
            .map_err(|e| CliError::Sweep(format!("cannot write the plan: {e}")))?;
        hagfish_run::replace_file(&path, (text + "\n").as_bytes()).map_err(CliError::from)
    }

    /// Reads the plan of the sweep folder `folder`; every run id must name a directory of
    /// its own under `runs/` ([`check_run_id`]), and `runs/` must not be a symbolic link, so
    /// that no run is written outside the folder.
    ///
    /// # Errors
    /// [`CliError::RunDirectory`] if `plan.json` is missing or malformed, [`CliError::Sweep`]
    /// for a run id that is not a plain name or a `runs/` that is a link.
    pub fn read(folder: &Path) -> Result<Self, CliError> {
        let path = folder.join(PLAN_FILE);
        let plan: Self = crate::manifest::read_json(path.clone())?;
        for run in &plan.runs {
            check_run_id(&run.id).map_err(|reason| {
                let id = hagfish_scenario::echo(&run.id);
                CliError::Sweep(format!("{}: run id {id:?}: {reason}", path.display()))
            })?;
        }
        let runs = folder.join(RUNS_DIRECTORY);
        if runs.symlink_metadata().is_ok_and(|m| m.file_type().is_symlink()) {
            return Err(CliError::Sweep(format!(
                "{}: is a symbolic link; a sweep writes its runs only inside its folder",
                runs.display()
            )));
        }
        Ok(plan)
    }

    /// Whether this plan holds every run of `earlier`, each with the same id, overrides and
    /// perturbation, over the same scenario and parameters: `earlier` with more replicates.
    fn extends(&self, earlier: &Plan) -> bool {
        self.scenario == earlier.scenario
            && self.parameters == earlier.parameters
            && earlier.runs.iter().all(|run| self.runs.contains(run))
    }

    /// The grid point of each run: runs with the same overrides are one point, numbered in
    /// the order of first appearance.
    pub fn points(&self) -> Vec<usize> {
        let mut seen: Vec<&[String]> = Vec::new();
        self.runs
            .iter()
            .map(|run| {
                seen.iter().position(|o| *o == run.overrides.as_slice()).unwrap_or_else(|| {
                    seen.push(&run.overrides);
                    seen.len() - 1
                })
            })
            .collect()
    }

    /// The run directory of `run` in the sweep folder `folder`.
    pub fn directory(folder: &Path, run: &PlannedRun) -> PathBuf {
        folder.join(RUNS_DIRECTORY).join(&run.id)
    }

    /// The value each swept parameter has in `run` (the last override of it; empty if the
    /// run does not set it).
    pub fn values(&self, run: &PlannedRun) -> Vec<String> {
        self.parameters
            .iter()
            .map(|p| {
                run.overrides
                    .iter()
                    .rev()
                    .filter_map(|o| o.split_once('='))
                    .find(|(path, _)| path.trim() == p)
                    .map_or_else(String::new, |(_, v)| v.trim().to_owned())
            })
            .collect()
    }
}

/// Refuses a run id that is not a plain directory name: empty, `.` or `..`, or holding a
/// character other than ASCII letters, digits, `-`, `_` and `.` (a `/` or `\\`, so no
/// absolute path and no `../x`), or longer than 100 characters.
///
/// # Errors
/// What is wrong with it.
pub fn check_run_id(id: &str) -> Result<(), &'static str> {
    let plain = |c: char| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.');
    if id.is_empty() || id == "." || id == ".." {
        Err("is not a directory name")
    } else if id.len() > 100 {
        Err("is longer than 100 characters")
    } else if !id.chars().all(plain) {
        Err("may hold only ASCII letters, digits, `-`, `_` and `.` (no path separator)")
    } else {
        Ok(())
    }
}

/// Parses `PATH=VALUE` texts.
fn parse_overrides(texts: &[String]) -> Result<Vec<Override>, CliError> {
    texts.iter().map(|t| Override::parse(t).map_err(CliError::from)).collect()
}

/// Whether the run in `directory` has ended for good (completed, diverged or tie failed):
/// a sweep leaves it alone.
pub fn ended(directory: &Path) -> Option<Status> {
    if !directory.join(MANIFEST_FILE).exists() {
        return None;
    }
    let status = Manifest::read(directory).ok()?.status;
    matches!(status, Status::Completed | Status::Diverged | Status::TieFailed).then_some(status)
}

/// Makes run `index` of the plan in `folder` unless it has ended: a new run, or the resumed
/// part of one that was stopped or killed. Returns how it ended.
///
/// # Errors
/// [`CliError`] if the plan cannot be read, `index` is out of range, or the run cannot start
/// or be recorded.
pub fn run_one(
    folder: &Path,
    plan: &Plan,
    index: usize,
    stop: &AtomicBool,
) -> Result<RunResult, CliError> {
    let run = plan.runs.get(index).ok_or_else(|| {
        CliError::Sweep(format!("no run {index}: the plan has {} runs", plan.runs.len()))
    })?;
    let directory = Plan::directory(folder, run);
    if let Some(status) = ended(&directory) {
        return Ok(RunResult::Skipped(status));
    }
    let texts: Vec<String> = run.overrides.iter().chain(&run.perturbation).cloned().collect();
    let overrides = parse_overrides(&texts)?;
    let request = RunRequest {
        source: Source::Scenario { path: &plan.scenario, overrides: &overrides },
        directory: &directory,
        existing: Existing::Resume,
        stop_after_frame: None,
        max_steps: None,
    };
    let finished = run_into_directory(&request, stop, &mut |_| {})?;
    Ok(RunResult::Ran(finished.manifest.status))
}

/// Which runs of a plan one process makes: shard i of n (counted from 1, as one says "part
/// 1 of 2") makes the runs whose index is i − 1 modulo n.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, from 1.
    pub number: usize,
    /// How many shards there are.
    pub count: usize,
}

impl Shard {
    /// Every run.
    pub const ALL: Shard = Shard { number: 1, count: 1 };

    /// Parses `i/n` with 1 ≤ i ≤ n. Shards count from 1: `0/n` is refused with the way to
    /// number a 0-based job array (`$((SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN + 1))`).
    ///
    /// # Errors
    /// [`CliError::Sweep`] for anything else.
    pub fn parse(text: &str) -> Result<Self, CliError> {
        let bad = |why: &str| CliError::Sweep(format!("--shard {text}: {why}"));
        let expected = "expected i/n with 1 ≤ i ≤ n (shard i of n)";
        let (i, n) = text.split_once('/').ok_or_else(|| bad(expected))?;
        let (number, count): (usize, usize) = (
            i.trim().parse().map_err(|_| bad(expected))?,
            n.trim().parse().map_err(|_| bad(expected))?,
        );
        match (number, count) {
            (0, _) => Err(bad(
                "shards count from 1 (1/n … n/n); from a Slurm array numbered from 0 or 1, \
                 pass $((SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN + 1))/$SLURM_ARRAY_TASK_COUNT",
            )),
            (number, count) if number <= count => Ok(Self { number, count }),
            _ => Err(bad(expected)),
        }
    }

    /// The indices of this shard among `runs` runs.
    pub fn indices(self, runs: usize) -> impl Iterator<Item = usize> {
        (self.number - 1..runs).step_by(self.count)
    }
}

/// Makes the runs of `shard` of the plan in `folder` on `jobs` threads (each run on one
/// thread), calling `report(index, result, seconds)` as each ends; stops starting runs when
/// `stop` becomes true. Returns every result by run index.
///
/// # Errors
/// [`CliError`] if the plan cannot be read.
pub fn run_shard(
    folder: &Path,
    shard: Shard,
    jobs: usize,
    stop: &AtomicBool,
    report: &(dyn Fn(usize, &RunResult, f64) + Sync),
) -> Result<Vec<(usize, RunResult)>, CliError> {
    let plan = Plan::read(folder)?;
    let indices: Vec<usize> = shard.indices(plan.runs.len()).collect();
    let next = AtomicUsize::new(0);
    let results = Mutex::new(Vec::with_capacity(indices.len()));
    std::thread::scope(|scope| {
        for _ in 0..jobs.clamp(1, indices.len().max(1)) {
            scope.spawn(|| {
                while !stop.load(Ordering::Relaxed) {
                    let Some(&index) = indices.get(next.fetch_add(1, Ordering::Relaxed)) else {
                        break;
                    };
                    let started = Instant::now();
                    let result = run_one(folder, &plan, index, stop)
                        .unwrap_or_else(|e| RunResult::Failed(e.to_string()));
                    report(index, &result, started.elapsed().as_secs_f64());
                    if let Ok(mut results) = results.lock() {
                        results.push((index, result));
                    }
                }
            });
        }
    });
    let mut results = results.into_inner().unwrap_or_else(std::sync::PoisonError::into_inner);
    results.sort_by_key(|(index, _)| *index);
    Ok(results)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_example_grid_plans_its_points_with_their_replicates() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/timestep_grid.ron");
        let grid = Grid::read(&path).expect("the example grid");
        let plan = Plan::of(&grid, &path).expect("its plan");
        assert_eq!(plan.runs.len(), 9 * 4);
        assert_eq!(plan.points(), (0..9).flat_map(|p| [p; 4]).collect::<Vec<_>>());
        let ids: Vec<&str> = plan.runs[..5].iter().map(|r| r.id.as_str()).collect();
        assert_eq!(ids, ["0000", "0000-1", "0000-2", "0000-3", "0001"]);
        assert!(plan.runs[0].perturbation.is_empty());
        assert_eq!(plan.runs[1].perturbation, [format!("time_step_s={:?}", 0.005 * (1.0 + 1e-12))]);
        let fewer = Plan::with_runs(plan.scenario.clone(), vec![plan.runs[0].overrides.clone()], 2)
            .expect("a plan");
        assert!(plan.extends(&fewer) && !fewer.extends(&plan));
        for bad in [0, MAX_REPLICATES + 1] {
            let refused = Plan::with_runs(plan.scenario.clone(), vec![Vec::new()], bad);
            assert!(refused.is_err_and(|e| e.to_string().contains("replicates")), "{bad}");
        }
    }

    #[test]
    fn shards_split_the_runs_without_overlap() {
        let shards: Vec<Vec<usize>> =
            (1..=3).map(|i| Shard { number: i, count: 3 }.indices(8).collect()).collect();
        assert_eq!(shards, vec![vec![0, 3, 6], vec![1, 4, 7], vec![2, 5]]);
        assert_eq!(Shard::parse("4/4").ok(), Some(Shard { number: 4, count: 4 }));
        for bad in ["0/4", "5/4", "1", "a/2", "-1/2", "1/0"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        let zero = Shard::parse("0/2").err().map(|e| e.to_string()).unwrap_or_default();
        assert!(zero.contains("count from 1"), "{zero}");
    }
}
