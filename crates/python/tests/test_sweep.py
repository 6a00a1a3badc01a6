"""Sweeps: a Dask LocalCluster of two worker processes gives the rows of the same runs made
serially; an interrupted sweep, rerun, makes only what is missing; the command line collects
a sweep planned from Python."""

import json
import subprocess
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import hagfish

GRID = {"time_step_s": [0.01, 0.02], "drag.quadratic_g_per_cm3": [0.5, 0.75, 1.0]}


def comparable(table: pd.DataFrame) -> pd.DataFrame:
    """A summary without the wall time, the only column equal runs differ in."""
    return table.drop(columns=["wall_time_s"]).reset_index(drop=True)


def final_hashes(folder):
    return {
        run.name: json.loads((run / "manifest.json").read_text())["final_state_hash"]
        for run in sorted((folder / "runs").iterdir())
    }


def test_a_dask_sweep_equals_the_same_runs_made_serially(tmp_path, thesis):
    distributed = pytest.importorskip("distributed")
    scenario = hagfish.Scenario.load(thesis)
    serial = hagfish.sweep(scenario, GRID, out=tmp_path / "serial")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        parallel = hagfish.sweep(scenario, GRID, out=tmp_path / "dask", executor=client)
    assert len(serial) == 6 and list(serial.status) == ["completed"] * 6
    assert list(serial["time_step_s"]) == [0.01, 0.01, 0.01, 0.02, 0.02, 0.02]
    pd.testing.assert_frame_equal(comparable(serial), comparable(parallel))
    assert final_hashes(tmp_path / "serial") == final_hashes(tmp_path / "dask")
    assert set(serial.final_knot) == {"3_1"}


def test_an_interrupted_sweep_rerun_makes_only_the_missing_runs(tmp_path, thesis):
    scenario = hagfish.Scenario.load(thesis, time_step_s=0.02)
    grid = [{"drag.quadratic_g_per_cm3": d} for d in (0.5, 0.75, 1.0)]
    folder = tmp_path / "sweep"
    # As if the sweep had stopped: run 0 made, run 1 cut off after 40 frames, run 2 not begun.
    ids = hagfish._native.sweep_plan(
        str(scenario.path),
        [scenario.set_arguments() + [f"drag.quadratic_g_per_cm3={d}"] for d in (0.5, 0.75, 1.0)],
        str(folder),
    )
    assert ids == ["0000", "0001", "0002"]
    hagfish.sweeps.run_planned(str(folder), 0)
    first = json.loads((folder / "runs/0000/manifest.json").read_text())
    cut = scenario.with_overrides({"drag.quadratic_g_per_cm3": 0.75})
    hagfish.run(cut, out=folder / "runs/0001", progress=False, stop_after_frames=40)
    assert hagfish.sweeps.open_sweep(folder).status.tolist() == [
        "completed", "interrupted", "missing"]

    table = hagfish.sweep(scenario, grid, out=folder, executor=ThreadPoolExecutor(2))
    assert table.status.tolist() == ["completed"] * 3
    again = json.loads((folder / "runs/0000/manifest.json").read_text())
    assert again["started_utc"] == first["started_utc"], "run 0 was not made again"
    resumed = json.loads((folder / "runs/0001/manifest.json").read_text())
    assert resumed["resumed_at_frames"] == [41], "run 1 was resumed, not restarted"
    assert resumed["final_state_hash"] == hagfish.run(
        cut, out=tmp_path / "whole", progress=False, pictures=False).summary["final_state_hash"]


def test_the_command_line_collects_a_sweep_planned_in_python(tmp_path, thesis, hagfish_bin):
    scenario = hagfish.Scenario.load(thesis, time_step_s=0.02)
    folder = tmp_path / "sweep"
    table = hagfish.sweep(scenario, {"drag.quadratic_g_per_cm3": [0.5, 1.0]}, out=folder)
    (folder / "summary.csv").unlink()
    subprocess.run([str(hagfish_bin), "sweep", "collect", str(folder)], check=True,
                   capture_output=True)
    collected = pd.read_csv(folder / "summary.csv", dtype={"id": str})
    pd.testing.assert_frame_equal(comparable(table), comparable(collected))
    with pytest.raises(hagfish.HagfishError, match="holds another plan"):
        hagfish.sweep(scenario, {"drag.quadratic_g_per_cm3": [0.25]}, out=folder)


def test_a_run_that_cannot_be_made_does_not_stop_the_others(tmp_path, thesis):
    import fcntl

    scenario = hagfish.Scenario.load(thesis, time_step_s=0.02)
    grid = {"drag.quadratic_g_per_cm3": [0.5, 0.75, 1.0]}
    folder = tmp_path / "sweep"
    busy = folder / "runs" / "0001"
    busy.mkdir(parents=True)
    with open(busy / ".hagfish.lock", "w") as lock:  # another process runs in run 1's folder
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        with pytest.raises(hagfish.HagfishError, match=r"1 of 3 runs could not be made") as error:
            hagfish.sweep(scenario, grid, out=folder, progress=False)
    assert "run 0001" in error.value.args[0] and "in use" in error.value.args[0]
    assert hagfish.open_sweep(folder).status.tolist() == ["completed", "missing", "completed"]
    # Once the folder is free, running the sweep again makes run 1 only.
    table = hagfish.sweep(scenario, grid, out=folder, progress=False)
    assert table.status.tolist() == ["completed"] * 3


def test_a_replicated_grid_gives_the_same_rows_by_cli_shards_and_by_python_on_dask(
        tmp_path, thesis, hagfish_bin, capsys):
    distributed = pytest.importorskip("distributed")
    grid_file = tmp_path / "grid.ron"
    grid_file.write_text(
        f'Sweep(scenario: "{thesis}", grid: [("time_step_s", ["0.02"]), '
        f'("drag.quadratic_g_per_cm3", ["0.5", "1.0"])], replicates: 2)\n')
    cli = tmp_path / "cli"
    for command in (["plan", str(grid_file), "--out", str(cli)],
                    ["run", str(cli), "--shard", "1/2"], ["run", str(cli), "--shard", "2/2"],
                    ["collect", str(cli)]):
        subprocess.run([str(hagfish_bin), "sweep", *command], check=True, capture_output=True)
    scenario = hagfish.Scenario.load(thesis)
    grid = {"time_step_s": [0.02], "drag.quadratic_g_per_cm3": [0.5, 1.0]}
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        table = hagfish.sweep(scenario, grid, out=tmp_path / "py", executor=client, replicates=2)
    by_cli = pd.read_csv(cli / "summary.csv", dtype={"id": str}, keep_default_na=False,
                         na_values=[""])
    pd.testing.assert_frame_equal(comparable(by_cli), comparable(table))
    assert list(table.id) == ["0000", "0000-1", "0001", "0001-1"]
    assert list(table.replicate) == [0, 1, 0, 1] and list(table.point) == [0, 0, 1, 1]
    # The replicates differ at rounding level, so their knots' paths differ.
    assert final_hashes(cli)["0000"] != final_hashes(cli)["0000-1"]

    def without_wall_time(intervals):
        return intervals[intervals.statistic != "wall_time_s"].reset_index(drop=True)

    cli_intervals = pd.read_csv(cli / "intervals.csv", keep_default_na=False, na_values=[""])
    intervals = hagfish.open_intervals(tmp_path / "py")
    pd.testing.assert_frame_equal(without_wall_time(cli_intervals), without_wall_time(intervals))
    travel = intervals[intervals.statistic == "core_travel_L"].set_index("point")
    means = table.groupby("point").core_travel_L.mean()
    assert np.allclose(travel["mean"], means, rtol=1e-12)
    assert (travel.n == 2).all() and travel.ci_low.isna().all(), "2 runs give no bootstrap-t"
    tied = intervals[intervals.statistic == "tied_share"]
    assert ((tied.ci_low <= tied["mean"]) & (tied["mean"] <= tied.ci_high)).all()

    # The same study with a third replicate makes only the third.
    capsys.readouterr()
    again = hagfish.sweep(scenario, grid, out=tmp_path / "py", replicates=3)
    assert list(again.id) == ["0000", "0000-1", "0000-2", "0001", "0001-1", "0001-2"]
    lines = capsys.readouterr().err.splitlines()
    made = [line.split()[2] for line in lines if not line.split(": ", 1)[1].startswith("already")]
    assert made == ["0000-2", "0001-2"], lines


@pytest.mark.parametrize("first, task, shard", [(0, 0, "1/8"), (0, 7, "8/8"), (1, 1, "1/8"),
                                                (1, 8, "8/8")])
def test_the_slurm_script_numbers_its_shards_from_any_first_array_index(
        tmp_path, first, task, shard):
    """`examples/slurm_sweep.sh` under `--array=0-7` or `--array=1-8` runs every shard once
    (a stand-in `hagfish` records its arguments)."""
    fake = tmp_path / "bin" / "hagfish"
    fake.parent.mkdir()
    fake.write_text('#!/bin/sh\necho "$@"\n')
    fake.chmod(0o755)
    env = {"PATH": f"{fake.parent}:/usr/bin:/bin", "SLURM_ARRAY_TASK_ID": str(task),
           "SLURM_ARRAY_TASK_MIN": str(first), "SLURM_ARRAY_TASK_COUNT": "8"}
    script = Path(__file__).resolve().parents[3] / "examples" / "slurm_sweep.sh"
    done = subprocess.run(["bash", str(script), "SWEEP"], env=env, check=True,
                          capture_output=True, text=True)
    assert done.stdout.split() == ["sweep", "run", "SWEEP", "--shard", shard]
