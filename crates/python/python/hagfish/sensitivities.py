"""Global sensitivity of the knot's slide to the body's and the scenario's parameters: a
Sobol (or Morris) design from SALib, each sample a run (or several replicates) of a sweep on
any executor, and SALib's indices of each output with their confidence intervals.

``design`` maps a sample (a dict of the problem's names to values) to the runs' overrides,
so that a problem may be posed in the units a biologist thinks in (a stiffness factor on a
log scale, a length in cm) and turned into scenario paths and body files here::

    problem = {"names": ["length_cm", "log10_stiffness"], "bounds": [[35, 50], [-1, 1]]}

    def design(sample):
        body = es103.variant(f"bodies/{hash(tuple(sample.values()))}.ron",
                             length_cm=sample["length_cm"],
                             bending_stiffness_dyn_cm_per_rad=10 ** sample["log10_stiffness"])
        return {"body": body.path}

    result = hagfish.sensitivity(scenario, problem, design, out="studies/s", samples=32)
    result.indices          # output, parameter, S1, S1_conf, ST, ST_conf

Sobol's first-order index S1 is the share of an output's variance that one parameter explains
alone, the total index ST the share it takes part in (alone or with others); SALib's
``*_conf`` are the half-widths of their 95 % bootstrap intervals. The knot runs are chaotic,
so part of every output's variance is the run's own scatter: it shows as 1 − ΣS1 and widens
every interval; ``replicates`` averages it down (each sample's output is its replicates'
mean)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Dict, Mapping, Optional, Sequence

import numpy as np
import pandas as pd

from .scenario import PathLike, Scenario
from .sweeps import sweep

#: The outputs analysed by default: the knot's travel, speed, length change and slide force.
OUTPUTS = ("core_travel_L", "core_speed_cm_s", "core_length_change_rel", "slide_force_mean_dyn_cm")

#: Outputs whose missing value means zero: a run that did not tie did not move a knot.
ZERO_WHEN_MISSING = ("core_travel_L",)

Problem = Mapping[str, Any]


@dataclass(frozen=True)
class Sensitivity:
    """A sensitivity study's result: ``indices`` (one row per output and parameter: for Sobol
    ``S1``, ``S1_conf``, ``ST``, ``ST_conf``; for Morris ``mu_star``, ``mu_star_conf``,
    ``sigma``), ``samples`` (one row per sample: its values and its outputs, the mean of its
    replicates, and ``completed``, how many of them completed rather than diverged or failed
    their tie), ``skipped`` (output → why it has no indices) and, with replicates, ``noise``
    (:func:`replicate_noise`; ``None`` with one run per sample)."""

    indices: pd.DataFrame
    samples: pd.DataFrame
    skipped: Dict[str, str]
    noise: Optional[pd.DataFrame] = None


def replicate_noise(table: pd.DataFrame, sample: np.ndarray, outputs: Sequence[str],
                    means: pd.DataFrame) -> pd.DataFrame:
    """The runs' own scatter over the whole design, from the replicates of each sample: per
    output the pooled replicate variance σ² (the mean over samples of each sample's variance,
    n − 1 divisor), the replicates per sample R, and η = (σ²/R) / Var(sample means), the share
    of the analysed means' variance that is noise. Jansen's total-index estimator counts η in
    every parameter's ST (E[(f(A) − f(A_B⁽ⁱ⁾))²]/2V gains σ²/R from each of the two
    independent evaluations, halved), so ST − η is the parameter's own share; the first-order
    estimator is unbiased by it."""
    grouped = table[list(outputs)].groupby(sample)
    within = grouped.var().mean()
    replicates = grouped.size().min()
    return pd.DataFrame({
        "output": list(outputs),
        "replicate_variance": [float(within[o]) for o in outputs],
        "replicates": int(replicates),
        "noise_share": [float(within[o] / replicates / means[o].var()) for o in outputs],
    })


def _salib(problem: Problem) -> dict:
    """SALib's problem dict: ``problem`` with ``num_vars`` (the number of names) if absent."""
    return {"num_vars": len(problem["names"]), **problem}


def design_samples(problem: Problem, samples: int, method: str = "sobol", seed: int = 0) -> np.ndarray:
    """The sample matrix (rows × parameters) of SALib's design: Saltelli's scheme for Sobol
    (``samples`` × (D + 2) rows, first-order and total indices only; ``samples`` a power of
    2), or ``samples`` Morris trajectories of D + 1 points (4 levels)."""
    if method == "sobol":
        from SALib.sample import sobol

        return sobol.sample(_salib(problem), samples, calc_second_order=False, seed=seed)
    if method == "morris":
        from SALib.sample import morris

        return morris.sample(_salib(problem), samples, num_levels=4, seed=seed)
    raise ValueError(f"method {method!r}: expected 'sobol' or 'morris'")


def indices(problem: Problem, x: np.ndarray, outputs: Mapping[str, np.ndarray], method: str = "sobol",
            seed: int = 0, missing: str = "skip") -> tuple:
    """SALib's indices of each output (a vector over the rows of ``x``) as one tidy table,
    and the outputs skipped. SALib's estimators need every sample: with ``missing="skip"`` an
    output with a missing value has no indices (and is said so), with ``missing="mean"`` each
    missing value is replaced by the mean of the others (a run that diverged before its slide,
    say; the count is in the table's ``imputed`` column — a few of hundreds move the indices
    far less than their intervals)."""
    if missing not in ("skip", "mean"):
        raise ValueError(f"missing={missing!r}: expected 'skip' or 'mean'")
    rows, skipped = [], {}
    for output, y in outputs.items():
        y = np.asarray(y, dtype=float)
        absent = ~np.isfinite(y)
        if absent.all() or (absent.any() and missing == "skip"):
            skipped[output] = f"{int(absent.sum())} of {len(y)} samples have no value"
            continue
        y = np.where(absent, y[~absent].mean(), y)
        if method == "sobol":
            from SALib.analyze import sobol

            # A Generator, not the int: SALib's Sobol analysis takes seed 0 for "unseeded".
            result = sobol.analyze(_salib(problem), y, calc_second_order=False, conf_level=0.95,
                                   seed=np.random.default_rng(seed))
            keys = ["S1", "S1_conf", "ST", "ST_conf"]
        else:
            from SALib.analyze import morris

            result = morris.analyze(_salib(problem), x, y, conf_level=0.95, num_levels=4, seed=seed)
            keys = ["mu_star", "mu_star_conf", "sigma"]
        for p, name in enumerate(problem["names"]):
            rows.append({"output": output, "parameter": name,
                         **{k: float(result[k][p]) for k in keys}, "imputed": int(absent.sum())})
    return pd.DataFrame(rows), skipped


def sensitivity(
    scenario: Scenario | PathLike,
    problem: Problem,
    design: Optional[Callable[[Dict[str, float]], Mapping[str, Any]]] = None,
    *,
    out: PathLike,
    samples: int = 32,
    method: str = "sobol",
    outputs: Sequence[str] = OUTPUTS,
    replicates: int = 1,
    executor: Any = None,
    seed: int = 0,
    missing: str = "skip",
    progress: bool = True,
) -> Sensitivity:
    """Samples ``problem`` (SALib's dict: ``names``, ``bounds``, optionally ``dists``) with
    :func:`design_samples`, runs each sample as a grid point of a sweep into ``out`` (its
    overrides from ``design``, by default the names as scenario paths), ``replicates`` times,
    on ``executor`` (see :func:`hagfish.sweep`), and returns the indices of each of
    ``outputs`` (columns of the sweep's summary) with :func:`indices`. Writes
    ``out/sensitivity.csv``, ``out/samples.csv`` and, with replicates, ``out/noise.csv``
    (:func:`replicate_noise`). Rerunning makes only the missing runs.
    A missing travel (no knot) counts as 0; another output's missing values are handled as
    ``missing`` says (see :func:`indices`). ``samples.csv`` keeps them missing."""
    x = design_samples(problem, samples, method, seed)
    names = list(problem["names"])
    points = [dict(zip(names, map(float, row))) for row in x]
    design = design or (lambda sample: sample)
    grid = [dict(design(point)) for point in points]
    folder = Path(out)
    table = sweep(scenario, grid, out=folder / "sweep", executor=executor, replicates=replicates,
                  progress=progress)
    # The summary's rows are the samples' runs in order, `replicates` each (two samples
    # that happen to be equal, as Morris' levels allow, are still two rows).
    sample = np.arange(len(table)) // replicates
    means = table[list(outputs)].groupby(sample).mean().reindex(range(len(points)))
    means["completed"] = (table.status == "completed").groupby(sample).sum()
    for output in ZERO_WHEN_MISSING:
        if output in means:
            means[output] = means[output].fillna(0.0)
    found, skipped = indices(problem, x, {o: means[o].to_numpy() for o in outputs}, method, seed,
                             missing)
    sampled = pd.concat([pd.DataFrame(x, columns=names), means.reset_index(drop=True)], axis=1)
    found.to_csv(folder / "sensitivity.csv", index=False)
    sampled.to_csv(folder / "samples.csv", index=False)
    noise = replicate_noise(table, sample, outputs, means) if replicates > 1 else None
    if noise is not None:
        noise.to_csv(folder / "noise.csv", index=False)
    return Sensitivity(indices=found, samples=sampled, skipped=skipped, noise=noise)


__all__ = ["OUTPUTS", "Sensitivity", "design_samples", "indices", "replicate_noise", "sensitivity"]
