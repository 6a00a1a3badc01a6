"""hagfish: a hagfish tying a knot in its own body and sliding it to the head, from Python.

The simulator is the Rust program ``hagfish`` (CGS units: cm, g, s; dyn, dyn·cm); this
package runs it in-process (the GIL released while stepping) and reads its run directories
as pandas DataFrames and NumPy arrays::

    import hagfish
    scenario = hagfish.Scenario.load("data/scenarios/thesis.ron", time_step_s=0.02)
    run = hagfish.run(scenario, out="out/h02")
    run.summary["core_speed_cm_s"], run.metrics["knot_core_mid_L"], run.centreline.shape

    table = hagfish.sweep(scenario, {"time_step_s": [0.005, 0.01, 0.02]}, out="sweeps/h",
                          replicates=8)
    hagfish.open_intervals("sweeps/h")   # per grid point: mean, sd, 95 % interval

Every mistake raises :class:`HagfishError` with the message (file:line:column where there
is one) and exit code of the command line.
"""

from ._native import HagfishError, __version__
from .scenario import Body, Scenario, override_text, params
from .runs import Run, open_run, run
from . import modes, runs, sensitivities, sweeps
from .sweeps import open_intervals, open_sweep, sweep
from .sensitivities import Sensitivity, sensitivity

__all__ = [
    "Body",
    "HagfishError",
    "Run",
    "Scenario",
    "__version__",
    "Sensitivity",
    "open_intervals",
    "open_run",
    "open_sweep",
    "override_text",
    "modes",
    "params",
    "run",
    "runs",
    "sensitivities",
    "sensitivity",
    "sweep",
    "sweeps",
]
