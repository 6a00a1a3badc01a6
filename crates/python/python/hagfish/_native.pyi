"""Type stubs of the Rust module ``hagfish._native`` (``crates/python/src/lib.rs``)."""

from typing import Any, Callable, Optional

import numpy as np
import numpy.typing as npt

__version__: str

class HagfishError(Exception):
    """``args == (message, exit_code)``: the command line's message and exit code."""

def resolve(path: str, overrides: list[str], body: Optional[str] = None) -> str:
    """The resolved scenario (RON text) with ``PATH=VALUE`` overrides applied."""

def params() -> list[tuple[str, str, str, str]]:
    """(name, unit, default, meaning) of every scenario parameter."""

def body(path: str) -> dict[str, Any]:
    """The derived body: name, kind, length_cm, mass_g, bodies, dofs, rows."""

def run(
    scenario: str,
    overrides: list[str],
    out: str,
    existing: str,
    progress: Optional[Callable[[float, float, int, str, Optional[str]], Any]] = None,
    pictures: bool = True,
    stop_after_frames: Optional[int] = None,
) -> tuple[str, Optional[str]]:
    """Runs into ``out``; returns (status, error)."""

def summary(directory: str) -> dict[str, Any]:
    """The summary row of a run directory."""

def centreline(directory: str) -> npt.NDArray[np.float64]:
    """Body centres, frames × bodies × 3 (cm)."""

def modes(
    directory: str, phase: Optional[str] = None, kind: str = "all", modes: Optional[int] = None
) -> dict[str, Any]:
    """The arrays of one selection of ``modes.npz`` (float64/int64 arrays, ``axis`` a list of
    str, ``length_cm`` a float)."""

def sweep_plan(scenario: str, runs: list[list[str]], folder: str, replicates: int = 1) -> list[str]:
    """Writes plan.json (each grid point ``replicates`` times); returns the run ids."""

def sweep_run(folder: str, index: int) -> tuple[str, bool]:
    """Makes one planned run unless it has ended; returns (status, skipped)."""

def sweep_collect(folder: str) -> tuple[str, str]:
    """Writes summary.csv, intervals.csv and plots; returns the two tables' paths."""

def main(argv: list[str]) -> int:
    """The command line ``hagfish`` in-process (``argv[0]`` the program's name); returns its
    exit code."""
