"""run.modes: the POD of a real run's slide as NumPy arrays, the same as the command line's
modes.npz, and a decomposition that gives the recorded field back."""

import subprocess
from pathlib import Path

import numpy as np
import pytest

import hagfish


THESIS = Path(__file__).resolve().parents[3] / "data" / "scenarios" / "thesis.ron"


@pytest.fixture(scope="module")
def slide_run(tmp_path_factory):
    """The thesis scenario at h = 0.02 s (tie, tighten, slide), without pictures."""
    out = tmp_path_factory.mktemp("modes") / "run"
    scenario = hagfish.Scenario.load(THESIS, time_step_s=0.02)
    run = hagfish.run(scenario, out=out, progress=False, pictures=False)
    assert run.status == "completed"
    return run


def test_the_modes_of_the_slide_give_the_recorded_field_back(slide_run):
    m = slide_run.modes(phase="slide")
    slide = (slide_run.metrics["phase"] == "slide").to_numpy()
    recorded = slide_run.thigmo_force[: len(slide)][slide]
    frames, dofs = recorded.shape
    r = min(frames, dofs)
    assert dofs == 150 and frames > 2
    assert m.shapes.shape == (r, dofs) and m.time_courses.shape == (r, frames)
    assert m.singular_values.shape == (r,) and np.all(np.diff(m.singular_values) <= 0)
    assert m.energy_fractions.sum() == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(m.cumulative_fractions, np.cumsum(m.energy_fractions), atol=1e-12)
    np.testing.assert_allclose(m.shapes @ m.shapes.T, np.eye(r), atol=1e-10)
    scale = np.abs(recorded).max()
    np.testing.assert_allclose(m.field(), recorded, atol=1e-9 * scale)
    np.testing.assert_array_equal(m.time_s, slide_run.metrics["time_s"].to_numpy()[slide])
    assert list(m.modes_for) == [0.90, 0.95, 0.99]
    assert 1 <= m.modes_for[0.90] <= m.modes_for[0.95] <= m.modes_for[0.99] <= r
    assert m.cumulative_fractions[m.modes_for[0.90] - 1] >= 0.90 - 1e-12
    assert sorted(set(m.axis)) == ["X", "Y", "Z"] and len(m.axis) == dofs
    assert m.s_L == pytest.approx(m.s_cm / m.length_cm)
    assert np.isfinite(m.wave["phase_speed_cm_s"]) and np.isfinite(m.wave["knot_speed_cm_s"])


def test_one_kind_has_its_dofs_along_the_body_and_count_keeps_the_first_modes(slide_run):
    m = slide_run.modes(phase="slide", kind="bend-y", count=4)
    assert m.shapes.shape == (4, 50) and m.time_courses.shape[0] == 4
    assert set(m.axis) == {"Y"} and np.all(np.diff(m.s_cm) > 0)
    assert m.energy_fractions.shape[0] > 4, "the energies of every mode, not only the kept"


def test_the_command_line_writes_the_same_arrays_into_modes_npz(slide_run, hagfish_bin):
    subprocess.run(
        [str(hagfish_bin), "modes", str(slide_run.directory), "--phase", "slide"],
        check=True, capture_output=True,
    )
    with np.load(slide_run.directory / "modes" / "modes.npz") as npz:
        for kind in ["all", "bend", "bend-y", "bend-z", "twist"]:
            m = slide_run.modes(phase="slide", kind=kind, count=8)
            np.testing.assert_array_equal(npz[f"{kind}/shapes"], m.shapes)
            np.testing.assert_array_equal(npz[f"{kind}/time_courses"], m.time_courses)
            np.testing.assert_array_equal(npz[f"{kind}/energy_fractions"], m.energy_fractions)
            np.testing.assert_array_equal(npz[f"{kind}/s_cm"], m.s_cm)
            np.testing.assert_array_equal(npz[f"{kind}/axis"], m.axis)
            assert npz[f"{kind}/modes_for"].dtype == np.int64
            assert list(npz[f"{kind}/modes_for"]) == list(m.modes_for.values())
            assert float(npz[f"{kind}/length_cm"]) == m.length_cm


def test_a_phase_the_run_lacks_or_an_unknown_kind_raise(slide_run):
    with pytest.raises(hagfish.HagfishError, match="no frame of phase \"swim\""):
        slide_run.modes(phase="swim")
    with pytest.raises(ValueError, match="unknown DOF kind"):
        slide_run.modes(phase="slide", kind="roll")
