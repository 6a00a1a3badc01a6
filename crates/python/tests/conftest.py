"""Shared fixtures: the repository's scenarios and the `hagfish` program built by Cargo."""

import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
SCENARIOS = ROOT / "data" / "scenarios"


@pytest.fixture(scope="session")
def hagfish_bin() -> Path:
    """The command-line program: ``HAGFISH_BIN`` (set by ``cargo xtask test``), else
    ``hagfish`` on PATH, else ``$CARGO_TARGET_DIR/release/hagfish``."""
    given = os.environ.get("HAGFISH_BIN") or shutil.which("hagfish")
    if not given:
        target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
        given = str(target / "release" / "hagfish")
    path = Path(given)
    assert path.is_file(), f"the hagfish program is needed at {path}: cargo build --release"
    return path


@pytest.fixture
def thesis() -> Path:
    return SCENARIOS / "thesis.ron"
