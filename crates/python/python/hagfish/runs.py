"""Running a scenario and reading a run directory."""

from __future__ import annotations

import json
import sys
import tempfile
import time
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Optional, Union

import numpy as np
import pandas as pd

from . import _native
from .scenario import PathLike, Scenario

if TYPE_CHECKING:
    from .modes import Modes

Progress = Callable[[float, float, int, str, Optional[str]], Any]


class Run:
    """A run directory (``docs/outputs.md``), read lazily: each table or array is read from its
    file the first time it is asked for. Units are CGS and named in the columns."""

    def __init__(self, directory: PathLike) -> None:
        self.directory = Path(directory)
        if not (self.directory / "manifest.json").is_file():
            raise _native.HagfishError(
                f"{self.directory}: not a run directory (no manifest.json)", 2
            )

    def __repr__(self) -> str:
        return f"Run({str(self.directory)!r}, status={self.status!r})"

    @property
    def manifest(self) -> dict:
        """``manifest.json``: program, scenario and its hash, status, times, steps, files."""
        return json.loads((self.directory / "manifest.json").read_text())

    @property
    def status(self) -> str:
        """``completed``, ``interrupted``, ``diverged``, ``tie_failed`` or ``running``."""
        return self.manifest["status"]

    @property
    def error(self) -> Optional[str]:
        """What made a diverged or failed run stop (``None`` otherwise)."""
        return self.manifest.get("error")

    @property
    def summary(self) -> dict:
        """The run's numbers as a sweep's ``summary.csv`` has them (status, final knot, when it
        was tied, the knotted core's travel and speed, penetration maxima, force-field
        statistics, wall time; ``None`` where the run has no such number), plus the manifest's
        ``scenario_name``, ``overrides`` and ``final_state_hash``."""
        row = _native.summary(str(self.directory))
        manifest = self.manifest
        for key in ("scenario_name", "overrides", "final_state_hash", "unfinished_phase"):
            row[key] = manifest.get(key)
        return row

    def _csv(self, name: str) -> pd.DataFrame:
        return pd.read_csv(self.directory / name, keep_default_na=False, na_values=[""])

    @cached_property
    def metrics(self) -> pd.DataFrame:
        """``metrics.csv``: one row per frame (phase, contacts, knot type and core, maxima)."""
        return self._csv("metrics.csv")

    @cached_property
    def forces(self) -> pd.DataFrame:
        """``forces.csv``: constraint forces per frame, joint, axis and group (dyn·cm)."""
        return self._csv("forces.csv")

    @cached_property
    def contacts(self) -> pd.DataFrame:
        """``contacts.csv``: the self contacts of each frame."""
        return self._csv("contacts.csv")

    @cached_property
    def internal(self) -> Optional[pd.DataFrame]:
        """``internal.csv`` (tension, shear, twist and bending per joint), or ``None`` for a run
        directory written before it existed."""
        path = self.directory / "internal.csv"
        return self._csv("internal.csv") if path.is_file() else None

    @cached_property
    def centreline(self) -> np.ndarray:
        """Body centres, frames × bodies × 3 (cm)."""
        return _native.centreline(str(self.directory))

    @cached_property
    def q(self) -> np.ndarray:
        """Joint coordinates, frames × DOFs (rad), from ``q.npy``."""
        return np.load(self.directory / "q.npy")

    @cached_property
    def qdot(self) -> np.ndarray:
        """Joint velocities, frames × DOFs (rad/s), from ``qdot.npy``."""
        return np.load(self.directory / "qdot.npy")

    @cached_property
    def thigmo_force(self) -> np.ndarray:
        """The thigmotaxic force field, frames × DOFs (dyn·cm), from ``thigmo_force.npy``."""
        return np.load(self.directory / "thigmo_force.npy")

    def modes(
        self, phase: Optional[str] = None, kind: str = "all", count: Optional[int] = None
    ) -> "Modes":
        """The proper orthogonal decomposition of the thigmotaxic force field on the frames of
        ``phase`` (``metrics.csv``'s ``phase``, e.g. ``"slide"``; every frame with force if
        ``None``) and the DOFs of ``kind`` (``all``, ``bend``, ``bend-y``, ``bend-z``,
        ``twist``), as ``hagfish modes`` computes it: a :class:`hagfish.modes.Modes` of NumPy
        arrays (energy fractions, shapes modes × DOFs, arc lengths in cm, time courses modes ×
        frames, the travelling-wave fit). ``count`` keeps the first shapes and time courses
        only. Raises :class:`hagfish.HagfishError` for a phase the run does not have or a zero
        field, ``ValueError`` for an unknown kind."""
        from .modes import modes

        return modes(self.directory, phase, kind, count)


def open_run(directory: PathLike) -> Run:
    """The run in ``directory`` (made by ``hagfish run``, :func:`run` or a sweep)."""
    return Run(directory)


def _print_progress() -> Progress:
    """A progress callback printing a line to stderr every simulated second."""
    last = [-1.0, time.monotonic()]

    def show(t: float, duration: float, frames: int, phase: str, knot: Optional[str]) -> None:
        now = time.monotonic()
        if int(t) > last[0] or now - last[1] > 2.0 or t >= duration:
            last[0], last[1] = int(t), now
            print(
                f"t = {t:6.2f} / {duration:.2f} s  phase {phase}  knot {knot or '-'}  "
                f"frames {frames}",
                file=sys.stderr,
                flush=True,
            )

    return show


def run(
    scenario: Union[Scenario, PathLike],
    out: Optional[PathLike] = None,
    *,
    progress: Union[bool, Progress] = True,
    overwrite: bool = False,
    resume: bool = False,
    pictures: bool = True,
    stop_after_frames: Optional[int] = None,
) -> Run:
    """Runs ``scenario`` into the run directory ``out`` (a new temporary directory if
    ``None``) and returns it as a :class:`Run`.

    The same code as ``hagfish run SCENARIO --out DIR [--set …]`` makes the same files, bit
    for bit. ``overwrite`` replaces a run already in ``out`` (``--overwrite``), ``resume``
    continues a stopped one (``--resume``); without either a directory that holds a run is
    refused. ``progress`` is ``True`` (a line on stderr every simulated second), ``False``, or
    a callable ``progress(time_s, duration_s, frames, phase, knot)`` called after each frame.
    ``pictures`` writes the plots, animation, exports and ``report.html`` as the command line
    does. Ctrl-C stops the run after the step being taken (resumable with ``resume=True``)
    and raises ``KeyboardInterrupt``.

    A run that diverges or whose tie fails is returned, not raised: see ``Run.status`` and
    ``Run.error``. Mistakes in the scenario, body or overrides, or a directory in use, raise
    :class:`hagfish.HagfishError`."""
    if overwrite and resume:
        raise ValueError("overwrite and resume exclude each other")
    if not isinstance(scenario, Scenario):
        scenario = Scenario.load(scenario)
    directory = Path(tempfile.mkdtemp(prefix="hagfish-run-")) if out is None else Path(out)
    callback: Optional[Progress]
    if progress is True:
        callback = _print_progress()
    elif progress is False or progress is None:
        callback = None
    else:
        callback = progress
    existing = "replace" if overwrite else "resume" if resume else "refuse"
    _native.run(
        str(scenario.path),
        scenario.set_arguments(),
        str(directory),
        existing,
        progress=callback,
        pictures=pictures,
        stop_after_frames=stop_after_frames,
    )
    return Run(directory)
