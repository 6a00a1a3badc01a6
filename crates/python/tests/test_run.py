"""A run from Python is the command line's run, bit for bit; its tables and arrays read back
with their units; overrides change what they name and nothing else; mistakes raise with the
command line's message and place."""

import subprocess
from pathlib import Path

import numpy as np
import pytest

import hagfish

OUTPUTS = ["centreline.csv", "metrics.csv", "forces.csv", "contacts.csv", "internal.csv",
           "q.npy", "qdot.npy", "thigmo_force.npy", "internal.npy", "scenario.ron"]


def test_a_run_equals_the_command_lines_run_bit_for_bit(tmp_path, thesis, hagfish_bin):
    overrides = {"time_step_s": 0.02, "Thigmotaxis.parameters.tail_pull_dyn": 10}
    scenario = hagfish.Scenario.load(thesis, overrides)
    cli = tmp_path / "cli"
    subprocess.run(
        [str(hagfish_bin), "run", str(thesis), "--out", str(cli), "--quiet",
         "--set", "time_step_s=0.02", "--set", "Thigmotaxis.parameters.tail_pull_dyn=10"],
        check=True, capture_output=True,
    )
    run = hagfish.run(scenario, out=tmp_path / "py", progress=False)
    assert run.status == "completed"
    for name in OUTPUTS:
        assert (cli / name).read_bytes() == (run.directory / name).read_bytes(), name
    assert run.summary["final_state_hash"] == hagfish.open_run(cli).summary["final_state_hash"]
    # The arrays as NumPy reads them, and the centreline as frames × bodies × 3.
    frames = len(run.metrics)
    assert run.q.shape == (frames, 150) and run.qdot.shape == (frames, 150)
    np.testing.assert_array_equal(run.q, np.load(cli / "q.npy"))
    assert run.centreline.shape == (frames, 100, 3)
    last = run.centreline[-1]
    table = run.metrics.merge(run.metrics, on="frame")  # columns are unique and named
    assert "knot_core_mid_L" in run.metrics.columns and len(table) == frames
    rows = hagfish.open_run(cli)._csv("centreline.csv")
    final = rows[rows.frame == frames - 1][["x_cm", "y_cm", "z_cm"]].to_numpy()
    np.testing.assert_array_equal(last, final)
    assert {"tension_dyn", "bend_y_dyn_cm"} <= set(run.internal.columns)
    assert run.summary["final_knot"] == "3_1"


def test_an_override_changes_what_it_names_and_nothing_else(thesis):
    base = hagfish.Scenario.load(thesis).resolved.splitlines()
    for overrides, changed in [
        ({"time_step_s": 0.02}, ["time_step_s: 0.02"]),
        ({"phases[2].Thigmotaxis.until.seconds": 7.5}, ["seconds: 7.5"]),
        ({"drag": {"linear_dyn_s_per_cm3": 0.25, "quadratic_g_per_cm3": 0.5}},
         ["linear_dyn_s_per_cm3: 0.25"]),
    ]:
        lines = hagfish.Scenario.load(thesis, overrides).resolved.splitlines()
        assert len(lines) == len(base)
        differing = [new.strip().rstrip(",") for old, new in zip(base, lines) if old != new]
        assert differing == changed, differing
    # Keyword arguments are the same overrides.
    assert hagfish.Scenario.load(thesis, time_step_s=0.02).resolved == \
        hagfish.Scenario.load(thesis, {"time_step_s": 0.02}).resolved


def test_bad_overrides_and_files_raise_with_their_place(tmp_path, thesis):
    with pytest.raises(hagfish.HagfishError) as error:
        hagfish.Scenario.load(thesis, {"time_step": 0.02})
    message, code = error.value.args
    assert "no field `time_step`" in message and code == 2
    with pytest.raises(hagfish.HagfishError, match="time_step_s"):
        hagfish.Scenario.load(thesis, time_step_s="fast")
    broken = tmp_path / "broken.ron"
    broken.write_text("Scenario(\n    name: \"x\",\n    time_step_s: ,\n)\n")
    with pytest.raises(hagfish.HagfishError, match=r"broken\.ron:3:\d+"):
        hagfish.Scenario.load(broken)
    body = tmp_path / "body.ron"
    body.write_text("Rod(\n    length_cm: -1.0,\n)\n")
    with pytest.raises(hagfish.HagfishError, match=r"body\.ron:\d+:\d+"):
        hagfish.Body.load(body)
    with pytest.raises(hagfish.HagfishError, match="not a run directory"):
        hagfish.open_run(tmp_path)


def test_a_directory_that_holds_a_run_is_refused_unless_asked(tmp_path, thesis):
    scenario = hagfish.Scenario.load(thesis, time_step_s=0.02, duration_s=2.0)
    out = tmp_path / "run"
    first = hagfish.run(scenario, out=out, progress=False, stop_after_frames=5)
    assert first.status == "interrupted"
    with pytest.raises(hagfish.HagfishError, match="holds a run"):
        hagfish.run(scenario, out=out, progress=False)
    seen = []
    resumed = hagfish.run(scenario, out=out, progress=lambda *p: seen.append(p), resume=True)
    assert resumed.status == "completed" and resumed.manifest["resumed_at_frames"] == [6]
    assert seen and seen[-1][0] == pytest.approx(2.0)
    again = hagfish.run(scenario, out=out, progress=False, overwrite=True, pictures=False)
    assert again.summary["final_state_hash"] == resumed.summary["final_state_hash"]


def test_params_and_bodies_are_tables():
    table = hagfish.params()
    assert {"time_step_s", "drag.quadratic_g_per_cm3"} <= set(table.name)
    body = hagfish.Body.load(Path(__file__).resolve().parents[3] / "data/hagfish/es103.ron")
    assert (body.bodies, body.dofs, len(body.table)) == (100, 150, 100)
    assert body.table.mass_g.sum() == pytest.approx(body.mass_g, rel=1e-9)


def test_a_body_variant_changes_the_fields_asked_for(tmp_path):
    base = hagfish.Body.load(Path(__file__).resolve().parents[3] / "data/hagfish/es103.ron")
    long = base.variant(tmp_path / "long.ron", length_cm=50.0, mass_g=94.0)
    assert (long.length_cm, long.mass_g, long.bodies) == (50.0, 94.0, base.bodies)
    assert long.table.radius_cm.tolist() == base.table.radius_cm.tolist()
    with pytest.raises(KeyError, match="no top-level field `length`"):
        base.variant(tmp_path / "bad.ron", length=50.0)
    with pytest.raises(hagfish.HagfishError, match=r"bad\.ron:\d+:\d+"):
        base.variant(tmp_path / "bad.ron", length_cm=-1.0)


def test_the_gil_is_released_while_stepping(tmp_path, thesis):
    """Another Python thread keeps running during a run: the longest pause between two of its
    loop iterations stays far below the run's length (a run holding the GIL, with no progress
    callback to hand it back, would pause it for the whole run)."""
    import threading
    import time

    scenario = hagfish.Scenario.load(thesis, time_step_s=0.02)
    worker = threading.Thread(
        target=hagfish.run, args=(scenario,),
        kwargs={"out": tmp_path / "run", "progress": False, "pictures": False},
    )
    started = last = time.monotonic()
    longest = 0.0
    worker.start()
    while worker.is_alive():
        now = time.monotonic()
        longest, last = max(longest, now - last), now
    worker.join()
    length = time.monotonic() - started
    assert hagfish.open_run(tmp_path / "run").status == "completed"
    assert length > 0.4, f"the run took {length:.2f} s: too short to tell"
    assert longest < 0.25 * length, f"the main thread paused {longest:.3f} s of {length:.3f} s"


def test_python_values_become_the_command_lines_text():
    assert [hagfish.override_text(v) for v in (True, None, 0.02, 3, "Trefoil(Left)")] == [
        "true", "None", "0.02", "3", "Trefoil(Left)"]
    assert hagfish.override_text((1.0, 2.5)) == "(1.0, 2.5)"
    assert hagfish.override_text([5.6, 5.5]) == "[5.6, 5.5]"
    assert hagfish.override_text(Path("/a/b.ron")) == '"/a/b.ron"'
    assert hagfish.override_text({"v_a": -1.0, "v_b": (1, 2)}) == "(v_a: -1.0, v_b: (1, 2))"
    with pytest.raises(TypeError):
        hagfish.override_text(object())


def test_a_body_files_fields_are_read_as_written(tmp_path):
    body = hagfish.Body.load(Path(__file__).resolve().parents[3] / "data" / "hagfish" / "es103.ron")
    assert body.read_field("circumferences_cm") == [5.6, 5.5, 5.6, 4.3]
    assert body.read_field("length_cm") == body.length_cm
    with pytest.raises(KeyError, match="no top-level field `girth`"):
        body.read_field("girth")
    assert body.read_field("tail_taper") is None
