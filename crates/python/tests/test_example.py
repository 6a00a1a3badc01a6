"""The example study runs (in its quick form) and writes its table and figure."""

import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[3]


def test_the_slide_study_example_writes_its_table_and_figure(tmp_path):
    pytest.importorskip("matplotlib")
    subprocess.run(
        [sys.executable, str(ROOT / "examples" / "slide_study.py"), "--out", str(tmp_path),
         "--quick"],
        check=True, capture_output=True,
    )
    table = pd.read_csv(tmp_path / "slide_study.csv")
    assert len(table) == 4 and set(table.status) == {"completed"}
    assert table.slide_force_dyn_cm.gt(0).all() and table.core_speed_cm_s.notna().all()
    assert (tmp_path / "slide_study.png").stat().st_size > 10_000
