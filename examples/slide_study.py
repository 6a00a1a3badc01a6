"""How the slide's control force and the knot's speed change with bending stiffness and body
length: a parameter study of the thesis scenario (tie a trefoil, tighten, slide to the head)
on body variants of ES103.

    python examples/slide_study.py --out studies/slide            # 4 stiffnesses × 3 lengths
    python examples/slide_study.py --out studies/slide --dask     # the same on a Dask cluster
    python examples/slide_study.py --out /tmp/quick --quick       # 2 × 2, for a smoke test

Each run is a run directory under OUT/sweep/runs/; rerunning makes only the missing runs.
Writes OUT/slide_study.csv (one row per body) and OUT/slide_study.png. Units: cm, s, dyn·cm.
The slide force is the mean |f_thigmo| (the thigmotaxic generalized force, dyn·cm) over the
DOFs and the frames of the `slide` phase; the speed is the knotted core's head-ward speed
(least-squares over the middle 80 % of the slide, `core_speed_cm_s`).
"""

from __future__ import annotations

import argparse
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

import hagfish

ROOT = Path(__file__).resolve().parents[1]
ES103 = ROOT / "data" / "hagfish" / "es103.ron"
THESIS = ROOT / "data" / "scenarios" / "thesis.ron"


def bodies(folder: Path, stiffnesses, lengths) -> pd.DataFrame:
    """One body file per (bending stiffness, length): ES103 with the stiffness per joint of
    the thesis' 100-body chain (dyn·cm/rad) and the length changed, mass ∝ length (same
    density and girth)."""
    folder.mkdir(parents=True, exist_ok=True)
    base = hagfish.Body.load(ES103)
    rows = []
    for k in stiffnesses:
        for length in lengths:
            path = folder / f"es103_k{k:g}_L{length:g}.ron"
            base.variant(
                path,
                bending_stiffness_dyn_cm_per_rad=float(k),
                length_cm=float(length),
                mass_g=base.mass_g * length / base.length_cm,
            )
            rows.append({"body": str(path.resolve()), "bending_stiffness_dyn_cm_per_rad": k,
                         "length_cm": length})
    return pd.DataFrame(rows)


def slide_force(run: hagfish.Run) -> float:
    """Mean |f_thigmo| over the DOFs and the frames of the slide phase (dyn·cm)."""
    slide = (run.metrics.phase == "slide").to_numpy()
    return float(np.abs(run.thigmo_force[slide]).mean()) if slide.any() else float("nan")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, required=True, help="study folder")
    parser.add_argument("--quick", action="store_true", help="2 stiffnesses × 2 lengths")
    parser.add_argument("--dask", action="store_true", help="run on a Dask LocalCluster")
    args = parser.parse_args()
    stiffnesses = [0.5, 2.0] if args.quick else [0.5, 1.0, 2.0, 4.0]
    lengths = [35.0, 42.4] if args.quick else [35.0, 42.4, 50.0]

    design = bodies(args.out / "bodies", stiffnesses, lengths)
    scenario = hagfish.Scenario.load(THESIS)
    grid = [{"body": Path(b)} for b in design.body]
    if args.dask:
        from distributed import Client, LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
            table = hagfish.sweep(scenario, grid, out=args.out / "sweep", executor=client)
    else:
        with ProcessPoolExecutor(2) as pool:
            table = hagfish.sweep(scenario, grid, out=args.out / "sweep", executor=pool)

    # One run directory at a time: only the numbers of each are kept.
    forces = [slide_force(hagfish.open_run(args.out / "sweep" / "runs" / i)) for i in table.id]
    table = table.assign(slide_force_dyn_cm=forces)
    table["body"] = design.body.to_numpy()
    study = design.merge(table, on="body")
    columns = ["bending_stiffness_dyn_cm_per_rad", "length_cm", "status", "final_knot",
               "core_speed_cm_s", "core_travel_L", "slide_force_dyn_cm", "wall_time_s"]
    study[columns].to_csv(args.out / "slide_study.csv", index=False)
    print(study[columns].to_string(index=False))
    plot(study, args.out / "slide_study.png")


def plot(study: pd.DataFrame, path: Path) -> None:
    """Speed and slide force against bending stiffness, one line per body length."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, (speed, force) = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    for length, rows in study.groupby("length_cm"):
        rows = rows.sort_values("bending_stiffness_dyn_cm_per_rad")
        label = f"L = {length:g} cm"
        speed.plot(rows.bending_stiffness_dyn_cm_per_rad, rows.core_speed_cm_s, "o-", label=label)
        force.plot(rows.bending_stiffness_dyn_cm_per_rad, rows.slide_force_dyn_cm, "o-",
                   label=label)
    speed.axhline(2.0, color="grey", lw=0.8, ls="--", label="commanded 2 cm/s")
    for axes, title in [(speed, "knot speed (cm/s)"), (force, "mean |f_thigmo| in slide (dyn·cm)")]:
        axes.set_xscale("log", base=2)
        axes.set_xlabel("bending stiffness per joint (dyn·cm/rad, 100-body chain)")
        axes.set_title(title, fontsize=10)
        axes.legend(fontsize=8)
    figure.suptitle("Thesis scenario on ES103 variants", fontsize=11)
    figure.savefig(path, dpi=120)


if __name__ == "__main__":
    main()
