"""The example studies run (in their quick form) and write their tables, figures and readings;
the committed outputs in `examples/` are what the scripts make of their committed tables, so
the text quoted in the docs cannot drift from the numbers."""

import importlib.util
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "examples"


def example(name):
    """The example script `examples/<name>.py` as a module (its `main` not run)."""
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_quick(name, out):
    subprocess.run([sys.executable, str(EXAMPLES / f"{name}.py"), "--out", str(out), "--quick"],
                   check=True, capture_output=True)


def test_the_slide_study_writes_its_table_figure_and_reading(tmp_path):
    pytest.importorskip("matplotlib")
    run_quick("slide_study", tmp_path)
    study = pd.read_csv(tmp_path / "slide_study.csv")
    assert len(study) == 4 and (study.runs == 5).all() and (study.tied_share == 1).all()
    for statistic in ["core_speed_cm_s", "core_travel_L", "slide_force_mean_dyn_cm"]:
        low, high = study[statistic + "_ci_low"], study[statistic + "_ci_high"]
        assert (low <= high).all() and study[statistic].notna().all()
    assert (tmp_path / "slide_study.png").stat().st_size > 10_000
    assert (tmp_path / "slide_study.md").read_text() == example("slide_study").reading(study)


def test_the_committed_slide_study_reading_is_made_from_its_committed_table():
    committed = EXAMPLES / "slide_study"
    study = pd.read_csv(committed / "slide_study.csv")
    assert (committed / "slide_study.md").read_text() == example("slide_study").reading(study)
    assert (study.runs == 8).all()


def test_the_sensitivity_example_writes_its_indices_figure_and_reading(tmp_path):
    pytest.importorskip("SALib")
    pytest.importorskip("distributed")
    run_quick("slide_sensitivity", tmp_path)
    indices = pd.read_csv(tmp_path / "sensitivity.csv")
    samples = pd.read_csv(tmp_path / "samples.csv")
    noise = pd.read_csv(tmp_path / "noise.csv")
    assert len(samples) == 2 * (4 + 2) and set(noise.replicates) == {2}
    # The replicates differ at rounding level, so every output has a scatter of its own.
    assert (noise.noise_share > 0).all()
    assert list(noise.output) == list(example("slide_sensitivity").LABELS)
    assert set(indices.parameter) <= set(example("slide_sensitivity").PROBLEM["names"])
    reading = example("slide_sensitivity").reading(indices, samples, noise)
    assert (tmp_path / "slide_sensitivity.md").read_text() == reading
    assert (tmp_path / "slide_sensitivity.png").stat().st_size > 10_000


def test_the_committed_sensitivity_reading_is_made_from_its_committed_tables():
    committed = EXAMPLES / "slide_sensitivity"
    tables = [pd.read_csv(committed / f) for f in ["sensitivity.csv", "samples.csv", "noise.csv"]]
    reading = example("slide_sensitivity").reading(*tables)
    assert (committed / "slide_sensitivity.md").read_text() == reading
