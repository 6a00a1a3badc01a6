"""The ``hagfish`` command that ``pip install`` puts in the environment's ``bin``
(``[project.scripts]``) and ``python -m hagfish``: the Rust program's command line run
in-process (``hagfish._native.main``), with its arguments, output and exit codes."""

import sys

from . import _native


def main() -> None:
    """Runs ``hagfish`` with ``sys.argv[1:]`` and exits with its exit code."""
    sys.exit(_native.main(["hagfish", *sys.argv[1:]]))
