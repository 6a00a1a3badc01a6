"""Parameter sweeps: the Cartesian product (or a list) of overrides, one run directory each
under a sweep folder, run serially or on any executor (``concurrent.futures`` or a Dask
``distributed.Client``), collected into one tidy DataFrame.

The folder has the layout of ``hagfish sweep plan`` (``plan.json``, ``runs/<id>/``,
``summary.csv``, ``intervals.csv``, ``plots/``), so the command line can run or collect a sweep
planned here and the other way round. A run that has ended (completed, diverged, tie failed)
is never made again: rerunning an interrupted sweep, or the same sweep with more replicates,
makes only the missing runs, and resumes the one that was cut off from its last frame.

The knot runs are chaotic (a change of the time step by parts in 10¹² moves the knot by
centimetres), so a study should run each grid point several times: ``replicates=N`` runs
replicate j with the time step h(1 + j·10⁻¹²), and :func:`open_intervals` gives each grid
point's mean, spread and 95 % interval of every statistic."""

from __future__ import annotations

import itertools
import sys
import time
from pathlib import Path
from typing import Any, Callable, Iterable, List, Mapping, Sequence, Union

import pandas as pd

from . import _native
from .scenario import PathLike, Scenario, override_text

Grid = Union[Mapping[str, Sequence[Any]], Sequence[Mapping[str, Any]]]


def combinations(grid: Grid) -> List[dict]:
    """The runs of ``grid``: a dict of path → values gives their Cartesian product (the last
    path varies fastest); a list of dicts is taken as it is."""
    if isinstance(grid, Mapping):
        paths = list(grid)
        return [dict(zip(paths, values)) for values in itertools.product(*grid.values())]
    return [dict(run) for run in grid]


def run_planned(folder: str, index: int) -> tuple:
    """Makes run ``index`` of the sweep planned in ``folder`` unless it has ended; returns
    ``(status, skipped)``. A top-level function, so that executors can pickle it."""
    return _native.sweep_run(folder, index)


def _is_dask(executor: Any) -> bool:
    return type(executor).__module__.split(".")[0] == "distributed"


def sweep(
    scenario: Union[Scenario, PathLike],
    grid: Grid,
    out: PathLike,
    *,
    executor: Any = None,
    replicates: int = 1,
    progress: bool = True,
) -> pd.DataFrame:
    """Runs ``scenario`` once per combination of ``grid`` (see :func:`combinations`), each
    into ``out/runs/<id>``, ``replicates`` times each (replicate j at the time step
    h(1 + j·10⁻¹²); j = 0 is the run as written), and returns ``summary.csv`` as a DataFrame:
    one row per run with its id, its grid point, the value of each swept path, its
    replicate, then status, final knot, tie time, the share of frames the knot held, the
    knotted core's travel, speed and length change, penetration maxima, force-field
    statistics and wall time (units in the column names). :func:`open_intervals` gives the
    same sweep per grid point, with intervals.

    ``executor`` is ``None`` (one run after another in this process), a
    ``concurrent.futures`` executor, or a Dask ``distributed.Client`` (a ``LocalCluster`` or
    a ``dask_jobqueue`` cluster's client); each task makes one run and returns only its
    status, so no run's arrays are held in memory. The scenario's own overrides apply to
    every run, before the grid's. Re-running the same sweep into the same folder makes only
    the runs that have not ended; another plan in that folder is refused. ``progress`` prints
    a line on stderr as each run's result arrives (in the order of the runs). A run that
    cannot be made (its directory in use by another process, a body file gone) does not stop
    the others: the summary is written, then :class:`hagfish.HagfishError` lists those runs.
    A run that diverges or fails its tie is a row with that status, not an error."""
    if not isinstance(scenario, Scenario):
        scenario = Scenario.load(scenario)
    folder = Path(out).resolve()
    base = scenario.set_arguments()
    runs = [
        base + [f"{path}={override_text(value)}" for path, value in run.items()]
        for run in combinations(grid)
    ]
    points = runs
    ids = _native.sweep_plan(str(scenario.path), points, str(folder), replicates)
    runs = [run for run in points for _ in range(replicates)]
    indices: Iterable[int] = range(len(ids))
    started = time.monotonic()

    failed: List[str] = []

    def report(index: int, outcome: Callable[[], tuple]) -> None:
        """Takes one run's result (its exception kept for the end), prints its line."""
        try:
            status, skipped = outcome()
            done = "already " + status if skipped else status
        except _native.HagfishError as error:
            failed.append(f"run {ids[index]}: {error.args[0]}")
            done = "failed: " + error.args[0]
        if progress:
            elapsed = time.monotonic() - started
            print(f"[{index + 1}/{len(ids)}] run {ids[index]} ({' '.join(runs[index][len(base):])}): "
                  f"{done}, {elapsed:.1f} s into the sweep", file=sys.stderr, flush=True)

    if executor is None:
        for index in indices:
            report(index, lambda: run_planned(str(folder), index))
    else:
        submit = executor.submit
        if _is_dask(executor):
            futures = [submit(run_planned, str(folder), i, pure=False) for i in indices]
        else:
            futures = [submit(run_planned, str(folder), i) for i in indices]
        for index, future in enumerate(futures):
            report(index, future.result)
    summary, _ = _native.sweep_collect(str(folder))
    if failed:
        raise _native.HagfishError(
            f"{len(failed)} of {len(ids)} runs could not be made (the others are in "
            f"{summary}):\n" + "\n".join(failed), 2)
    return _read(summary)


def _read(table: PathLike) -> pd.DataFrame:
    """A table of the sweep folder: ids as text, empty fields as NaN, text kept as it is."""
    return pd.read_csv(table, dtype={"id": str}, keep_default_na=False, na_values=[""])


def open_sweep(out: PathLike) -> pd.DataFrame:
    """Collects the sweep in ``out`` (runs made so far; missing ones have status
    ``missing``) and returns its ``summary.csv``, one row per run."""
    summary, _ = _native.sweep_collect(str(Path(out).resolve()))
    return _read(summary)


def open_intervals(out: PathLike) -> pd.DataFrame:
    """Collects the sweep in ``out`` and returns its ``intervals.csv``: one row per grid
    point and statistic, over the point's ended runs — ``point``, the swept paths' values,
    ``runs``, ``statistic`` (a numeric column of the summary, or ``tied_share``,
    ``held_share``, ``slid_share``), ``n`` (runs with a value), ``mean``, ``sd`` (n − 1),
    ``ci_low``, ``ci_high`` (95 %: bootstrap-t of the mean, from 3 values on; Wilson for a
    share) and ``level``. ``table.pivot(index="point", columns="statistic", values="mean")``
    gives one row per point."""
    _, intervals = _native.sweep_collect(str(Path(out).resolve()))
    return _read(intervals)


__all__ = ["combinations", "open_intervals", "open_sweep", "run_planned", "sweep"]
