"""The modes of a run's thigmotaxic force field: its proper orthogonal decomposition on one
phase and one kind of DOF, as ``hagfish modes`` computes it (``docs/physics.md``, "Modes of the
force field")."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _native
from .scenario import PathLike

#: The order of :attr:`Modes.wave`'s numbers.
WAVE_FIELDS = (
    "k_rad_per_cm",
    "k_r_squared",
    "omega_rad_per_s",
    "omega_r_squared",
    "phase_speed_cm_s",
    "knot_speed_cm_s",
    "speed_ratio",
)


@dataclass(frozen=True)
class Modes:
    """F(t, s) = Σᵢ aᵢ(t) vᵢ(s) for the frames of ``phase`` and the DOFs of ``kind``: r =
    min(frames, DOFs) modes, of which ``shapes`` and ``time_courses`` hold the first k (all
    unless fewer were asked for). Units: dyn·cm for σ and a, cm for arc lengths, s for times."""

    phase: Optional[str]
    kind: str
    #: σᵢ, shape (r,), non-increasing.
    singular_values: np.ndarray
    #: σᵢ² / Σσ², shape (r,); they sum to 1.
    energy_fractions: np.ndarray
    #: The running sum of :attr:`energy_fractions`, shape (r,).
    cumulative_fractions: np.ndarray
    #: {0.90: n, 0.95: n, 0.99: n}: the fewest modes holding each fraction of the energy.
    modes_for: dict
    #: vᵢ(s), shape (k, DOFs), each of unit norm, its largest component positive.
    shapes: np.ndarray
    #: Each DOF's arc length from the head body's centre, shape (DOFs,) (cm).
    s_cm: np.ndarray
    #: The same over the body length L.
    s_L: np.ndarray
    #: Each DOF's axis: ``"X"`` twist, ``"Y"`` and ``"Z"`` bends, shape (DOFs,).
    axis: np.ndarray
    #: Each frame's time, shape (frames,) (s).
    time_s: np.ndarray
    #: aᵢ(t) = σᵢ uᵢ(t), shape (k, frames).
    time_courses: np.ndarray
    #: The knotted core's head-ward end in each frame (cm; NaN without a knot).
    knot_cm: np.ndarray
    #: The body length L (cm).
    length_cm: float
    #: Modes 1 and 2 as a travelling wave, named as :data:`WAVE_FIELDS` (NaN where there is
    #: none: a single mode, no knot speed).
    wave: dict

    def field(self) -> np.ndarray:
        """The field of the kept modes, Σᵢ aᵢ(t) vᵢ(s): frames × DOFs (dyn·cm); all modes give
        the recorded field back to rounding."""
        return self.time_courses.T @ self.shapes


def modes(
    directory: PathLike,
    phase: Optional[str] = None,
    kind: str = "all",
    count: Optional[int] = None,
) -> Modes:
    """The modes of the run in ``directory`` (see :meth:`hagfish.Run.modes`)."""
    arrays = _native.modes(str(directory), phase, kind, count)
    levels = [float(level) for level in arrays.pop("energy_levels")]
    counts = [int(n) for n in arrays.pop("modes_for")]
    wave = dict(zip(WAVE_FIELDS, (float(w) for w in arrays.pop("wave"))))
    axis = np.array(arrays.pop("axis"), dtype=str)
    return Modes(
        phase=phase,
        kind=kind,
        modes_for=dict(zip(levels, counts)),
        wave=wave,
        axis=axis,
        **arrays,
    )
