"""The slide's force field in the knot's frame: the energy k POD modes capture when each
frame's field is taken at r = s − s_knot(t) (s_knot the knotted core's head-ward end,
`knot_core_start_cm`) rather than at the body's own arc length s, per DOF kind, on ES103's
thesis run at REPLICATES rounding perturbations of its time step (h(1 + j·1e-12)).

    python bench/comoving_modes.py OUT [REPLICATES]      # default 8; a sweep folder OUT

If the field were a wave travelling with the knot, its knot-frame matrix would be of low
rank and a basis moving with the knot would need fewer modes than a fixed one (#37)."""

import sys
from pathlib import Path

import numpy as np

import hagfish

ROOT = Path(__file__).resolve().parents[1]
KS = [1, 2, 4, 8]
KINDS = {"Y": "bend-y", "Z": "bend-z", "X": "twist"}


def captured(matrix: np.ndarray) -> np.ndarray:
    """Cumulative energy fractions of the singular values of `matrix` (no mean removed)."""
    energy = np.linalg.svd(matrix, compute_uv=False) ** 2
    return np.cumsum(energy) / energy.sum()


def frames(run: hagfish.Run, axis: str) -> tuple:
    """The slide's field of one DOF axis at s (frames × DOFs) and the same frames resampled
    at r = s − s_knot on a grid of the DOF spacing over −L … L (zero off the body)."""
    metrics = run.metrics
    slide = (metrics.phase == "slide").to_numpy() & metrics.knot_core_start_cm.notna().to_numpy()
    modes = run.modes(phase="slide", kind="all")
    columns = modes.axis == axis
    s = modes.s_cm[columns]
    field = run.thigmo_force[: len(metrics)][slide][:, columns]
    knot = metrics.knot_core_start_cm.to_numpy()[slide]
    step = float(np.median(np.diff(s)))
    grid = np.arange(-s.max(), s.max() + step, step)
    moved = np.array([np.interp(grid, s - k, f, left=0.0, right=0.0) for k, f in zip(knot, field)])
    return field, moved


def main() -> None:
    out, replicates = Path(sys.argv[1]), int(sys.argv[2]) if len(sys.argv) > 2 else 8
    scenario = hagfish.Scenario.load(ROOT / "data" / "scenarios" / "thesis.ron")
    runs = hagfish.sweep(scenario, [{}], out=out, replicates=replicates, progress=False)
    table = {(a, frame): [] for a in KINDS for frame in ("body", "knot")}
    for run_id in runs.id:
        run = hagfish.open_run(out / "runs" / run_id)
        for axis in KINDS:
            field, moved = frames(run, axis)
            table[(axis, "body")].append(captured(field))
            table[(axis, "knot")].append(captured(moved))
    print(f"| kind | frame | " + " | ".join(f"k = {k}" for k in KS) + " |")
    print("|---|---|" + "---|" * len(KS))
    for (axis, frame), curves in table.items():
        ranges = [f"{min(c[k - 1] for c in curves):.2f}–{max(c[k - 1] for c in curves):.2f}"
                  for k in KS]
        print(f"| {KINDS[axis]} | {frame} | " + " | ".join(ranges) + " |")


if __name__ == "__main__":
    main()
