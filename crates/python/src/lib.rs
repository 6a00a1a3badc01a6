//! `hagfish._native`: the Rust side of the Python package `hagfish` (`python/hagfish`). It
//! runs scenarios into run directories with the same code as `hagfish run`
//! ([`hagfish::runner`]), with the GIL released while stepping, and reads what a run directory
//! holds that Python cannot read as simply (the centreline as a frames × bodies × 3 array, the
//! summary row, the modes of the force field). The Python layer (`hagfish/__init__.py` and its modules) turns these into
//! `Scenario`, `Body`, `Run` and `sweep`.
//!
//! Every error is raised as `hagfish.HagfishError(message, exit_code)` with the message the
//! command line prints after `error: ` (file:line:column where there is one) and the exit
//! code it would exit with.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use hagfish::CliError;
use hagfish::runner::{Existing, RunRequest, Source, body_override, run_into_directory};
use hagfish::study::RunRow;
use hagfish::sweep::{Plan, RunResult};
use hagfish_run::{NpyData, Progress};
use hagfish_scenario::{LoadedScenario, Override, PARAMETERS};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

create_exception!(
    _native,
    HagfishError,
    PyException,
    "An error of hagfish: args are (message, exit_code), the message and exit code of the \
     command line for the same mistake."
);

/// The Python exception of `error`.
fn raise(error: &CliError) -> PyErr {
    HagfishError::new_err((error.to_string(), error.exit_code()))
}

/// The Python exception of a scenario-crate error.
fn raise_scenario(error: hagfish_scenario::ScenarioError) -> PyErr {
    raise(&CliError::from(error))
}

/// Parses `PATH=VALUE` overrides.
fn parse_overrides(texts: &[String]) -> PyResult<Vec<Override>> {
    texts.iter().map(|t| Override::parse(t).map_err(raise_scenario)).collect()
}

/// The scenario `path` with `overrides` (and `body`, a body file, if given) applied, as the
/// resolved RON text `scenario.ron` would hold; raises for a bad file or override.
#[pyfunction]
#[pyo3(signature = (path, overrides, body=None))]
fn resolve(path: PathBuf, overrides: Vec<String>, body: Option<PathBuf>) -> PyResult<String> {
    let overrides = with_body(parse_overrides(&overrides)?, body.as_deref())?;
    let loaded = LoadedScenario::load_with(&path, &overrides).map_err(raise_scenario)?;
    Ok(loaded.resolved_text())
}

/// `overrides` followed by the override of `body`, if given.
fn with_body(mut overrides: Vec<Override>, body: Option<&Path>) -> PyResult<Vec<Override>> {
    if let Some(body) = body {
        overrides.push(body_override(body).map_err(|e| raise(&e))?);
    }
    Ok(overrides)
}

/// Every scenario parameter as (name, unit, default, meaning), as `hagfish params` lists them.
#[pyfunction]
fn params() -> Vec<(&'static str, &'static str, &'static str, &'static str)> {
    PARAMETERS.iter().map(|p| (p.name, p.unit, p.default, p.meaning)).collect()
}

/// The body file `path` derived (as `hagfish body` prints it): a dict with `name`, `kind`,
/// `length_cm`, `mass_g`, `bodies`, `dofs` and `rows`, a list of per-body dicts (`index`,
/// `s_over_L`, `radius_cm`, `mass_g`, `joint`).
#[pyfunction]
fn body<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let fail = |e: hagfish_anatomy::AnatomyError| raise(&CliError::from(e));
    let body = hagfish_anatomy::Body::load(&path).map_err(fail)?;
    let table = body.body_table().map_err(fail)?;
    let model = body.to_model().map_err(fail)?;
    let result = PyDict::new(py);
    result.set_item("name", body.name())?;
    let kind = match body {
        hagfish_anatomy::Body::Hagfish(_) => "hagfish",
        hagfish_anatomy::Body::Rod(_) => "rod",
    };
    result.set_item("kind", kind)?;
    result.set_item("length_cm", body.length_cm())?;
    result.set_item("mass_g", body.mass_g())?;
    result.set_item("bodies", model.body_count())?;
    result.set_item("dofs", model.dof_count())?;
    let rows = PyList::empty(py);
    for row in &table.rows {
        let r = PyDict::new(py);
        r.set_item("index", row.index)?;
        r.set_item("s_over_L", row.centre_fraction)?;
        r.set_item("radius_cm", row.radius_cm)?;
        r.set_item("mass_g", row.mass_g)?;
        r.set_item("joint", row.joint.name())?;
        rows.append(r)?;
    }
    result.set_item("rows", rows)?;
    Ok(result)
}

/// Runs `scenario` with `overrides` (`PATH=VALUE`, `body="FILE"` for another body) into `out`
/// with the GIL released; `existing`
/// is `"refuse"`, `"replace"` or `"resume"` (as `hagfish run`, `--overwrite`, `--resume`).
/// `progress(time_s, duration_s, frames, phase, knot)` is called after every recorded frame
/// (with the GIL); an exception from it (Ctrl-C included) stops the run after the step being
/// taken, leaving it resumable, and is raised once the run is recorded. With `pictures` the
/// plots, animation, exports and report are written too. Returns `(status, error)`: a run that
/// diverged or failed its tie is a result, not an exception.
#[pyfunction]
#[pyo3(signature = (scenario, overrides, out, existing, progress=None, pictures=true, stop_after_frames=None))]
#[allow(clippy::too_many_arguments)]
fn run(
    py: Python<'_>,
    scenario: PathBuf,
    overrides: Vec<String>,
    out: PathBuf,
    existing: &str,
    progress: Option<Py<PyAny>>,
    pictures: bool,
    stop_after_frames: Option<usize>,
) -> PyResult<(String, Option<String>)> {
    let overrides = parse_overrides(&overrides)?;
    let existing = match existing {
        "refuse" => Existing::Refuse,
        "replace" => Existing::Replace,
        "resume" => Existing::Resume,
        other => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "existing must be \"refuse\", \"replace\" or \"resume\", not {other:?}"
            )));
        }
    };
    let request = RunRequest {
        source: Source::Scenario { path: &scenario, overrides: &overrides },
        directory: &out,
        existing,
        stop_after_frame: stop_after_frames,
        max_steps: None,
    };
    let stop = AtomicBool::new(false);
    let mut raised: Option<PyErr> = None;
    let result = py.detach(|| {
        let mut report = |p: &Progress<'_>| {
            let Some(callback) = progress.as_ref() else { return };
            if raised.is_some() {
                return;
            }
            let knot = p.knot.map(|k| k.knot.to_string());
            let called = Python::attach(|py| {
                py.check_signals()?;
                callback.call1(py, (p.time, p.duration, p.frames, p.phase, knot)).map(drop)
            });
            if let Err(error) = called {
                raised = Some(error);
                stop.store(true, Ordering::Relaxed);
            }
        };
        let mut finished = run_into_directory(&request, &stop, &mut report)?;
        if pictures && raised.is_none() {
            finished.write_pictures()?;
        }
        Ok::<_, CliError>((finished.manifest.status.name().to_owned(), finished.manifest.error))
    });
    if let Some(error) = raised {
        return Err(error);
    }
    result.map_err(|e| raise(&e))
}

/// The summary row of the run in `directory` ([`RunRow`]) as a dict of the columns of a
/// sweep's `summary.csv` (`None` where the run has no such number).
#[pyfunction]
fn summary<'py>(py: Python<'py>, directory: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let row = RunRow::read(&directory).map_err(|e| raise(&e))?;
    let result = PyDict::new(py);
    for (column, value) in RunRow::COLUMNS.iter().zip(row.values()) {
        if value.is_empty() {
            result.set_item(column, py.None())?;
        } else if let Ok(number) = value.parse::<f64>() {
            result.set_item(column, number)?;
        } else {
            result.set_item(column, value)?;
        }
    }
    result.set_item("steps", row.steps)?;
    Ok(result)
}

/// The body centres of every frame of the run in `directory` (cm): a frames × bodies × 3
/// float64 array read from `centreline.csv`.
#[pyfunction]
fn centreline<'py>(py: Python<'py>, directory: PathBuf) -> PyResult<Bound<'py, PyAny>> {
    let read = hagfish_report::Centreline::read(&directory.join("centreline.csv"));
    let line = read.map_err(|e| raise(&CliError::from(e)))?;
    let frames = line.frames();
    let bodies = if frames == 0 { 0 } else { line.frame(0).len() };
    let values: Vec<f64> =
        (0..frames).flat_map(|f| line.frame(f).iter().flatten().copied()).collect();
    let array = PyArray1::from_vec(py, values).reshape([frames, bodies, 3])?;
    Ok(array.into_any())
}

/// The proper orthogonal decomposition of the thigmotaxic force field of the run in
/// `directory` on the frames of `phase` (every frame with force if `None`) and the DOFs of
/// `kind` (`all`, `bend`, `bend-y`, `bend-z`, `twist`), as `hagfish modes` computes it: a
/// dict of the arrays `modes.npz` holds per selection
/// ([`hagfish_modes::Decomposition::arrays`]; the first `modes` shapes and time courses, all
/// of them if `None`), float64 and int64 NumPy arrays, `axis` a list of str and `length_cm` a
/// float.
#[pyfunction]
#[pyo3(signature = (directory, phase=None, kind="all", modes=None))]
fn modes<'py>(
    py: Python<'py>,
    directory: PathBuf,
    phase: Option<String>,
    kind: &str,
    modes: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let kind: hagfish_modes::KindSelection =
        kind.parse().map_err(|e: String| pyo3::exceptions::PyValueError::new_err(e))?;
    let fail = |e: hagfish_modes::ModesError| raise(&CliError::from(e));
    let field = hagfish_modes::RunField::read(&directory).map_err(fail)?;
    let decomposition =
        hagfish_modes::Decomposition::of(&field, phase.as_deref(), kind).map_err(fail)?;
    let result = PyDict::new(py);
    for entry in decomposition.arrays(modes.unwrap_or(usize::MAX)) {
        let name = entry.name.as_str();
        match entry.data {
            NpyData::F64(values) if entry.shape.is_empty() => {
                result.set_item(name, values.first().copied().unwrap_or(f64::NAN))?;
            }
            NpyData::F64(values) => {
                result.set_item(name, PyArray1::from_vec(py, values).reshape(entry.shape)?)?;
            }
            NpyData::I64(values) => {
                result.set_item(name, PyArray1::from_vec(py, values).reshape(entry.shape)?)?;
            }
            NpyData::Text(values) => result.set_item(name, values)?,
        }
    }
    Ok(result)
}

/// Writes the plan of a sweep of `scenario` with one grid point per list of overrides, each
/// run `replicates` times, into `folder` (checked: a bad override raises naming the run);
/// returns the run ids.
#[pyfunction]
#[pyo3(signature = (scenario, runs, folder, replicates = 1))]
fn sweep_plan(
    scenario: PathBuf,
    runs: Vec<Vec<String>>,
    folder: PathBuf,
    replicates: usize,
) -> PyResult<Vec<String>> {
    let scenario = std::path::absolute(&scenario).map_err(|e| {
        raise(&CliError::RunDirectory { path: scenario.clone(), reason: e.to_string() })
    })?;
    let plan = Plan::with_runs(scenario, runs, replicates).map_err(|e| raise(&e))?;
    plan.write(&folder).map_err(|e| raise(&e))?;
    Ok(plan.runs.into_iter().map(|r| r.id).collect())
}

/// Makes run `index` of the sweep in `folder` unless it has ended (GIL released); returns
/// `(status, skipped)`.
#[pyfunction]
fn sweep_run(py: Python<'_>, folder: PathBuf, index: usize) -> PyResult<(String, bool)> {
    let plan = Plan::read(&folder).map_err(|e| raise(&e))?;
    let stop = AtomicBool::new(false);
    let result = py.detach(|| hagfish::sweep::run_one(&folder, &plan, index, &stop));
    match result.map_err(|e| raise(&e))? {
        RunResult::Skipped(status) => Ok((status.name().to_owned(), true)),
        RunResult::Ran(status) => Ok((status.name().to_owned(), false)),
        RunResult::Failed(message) => Err(raise(&CliError::Sweep(message))),
    }
}

/// Writes `summary.csv`, `intervals.csv` and the plots of the sweep in `folder`; returns the
/// two tables' paths.
#[pyfunction]
fn sweep_collect(py: Python<'_>, folder: PathBuf) -> PyResult<(PathBuf, PathBuf)> {
    py.detach(|| hagfish::sweep_summary::collect(&folder)).map_err(|e| raise(&e))?;
    let table = |name: &str| folder.join(name);
    Ok((table(hagfish::sweep_summary::SUMMARY_FILE), table(hagfish::sweep_summary::INTERVALS_FILE)))
}

/// The command line `hagfish` in-process, for the `hagfish` command pip installs and
/// `python -m hagfish`: `argv` as the program gets it (the program's name first). Returns
/// the exit code the program exits with: clap's for a usage mistake (2, with its message on
/// stderr) or `--help`/`--version` (0), else 0 or the error's code after `error: …` on stderr
/// (as `src/main.rs`). Runs with the GIL released; from the first `run` or `sweep run` on,
/// SIGINT and SIGTERM are the program's for the rest of the process (they stop the run
/// being made and are ignored between runs, as `ctrlc` keeps them), not Python's.
#[pyfunction]
fn main(py: Python<'_>, argv: Vec<String>) -> i32 {
    use clap::Parser;
    use std::io::Write;
    let code = match hagfish::cli::Cli::try_parse_from(argv) {
        Err(usage) => {
            // Nothing sensible is left to do if stdout or stderr itself is closed.
            let _ = usage.print();
            usage.exit_code()
        }
        Ok(cli) => py.detach(|| match hagfish::cli::run(cli) {
            Ok(()) => 0,
            Err(e) => {
                let _ = writeln!(std::io::stderr(), "error: {e}");
                i32::from(e.exit_code())
            }
        }),
    };
    let _ = std::io::stdout().flush();
    code
}

/// The module `hagfish._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("HagfishError", m.py().get_type::<HagfishError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(resolve, m)?)?;
    m.add_function(wrap_pyfunction!(params, m)?)?;
    m.add_function(wrap_pyfunction!(body, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(summary, m)?)?;
    m.add_function(wrap_pyfunction!(centreline, m)?)?;
    m.add_function(wrap_pyfunction!(modes, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_plan, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_run, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_collect, m)?)?;
    m.add_function(wrap_pyfunction!(main, m)?)?;
    Ok(())
}
