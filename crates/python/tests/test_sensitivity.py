"""Sensitivity studies: SALib's Sobol indices, as `hagfish.sensitivities` computes them, hold
the Ishigami function's exact indices within their intervals; a small study of the thesis
scenario runs end to end on an executor and reruns nothing."""

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import hagfish
from hagfish.sensitivities import design_samples, indices

pytest.importorskip("SALib")

ISHIGAMI = {"names": ["x1", "x2", "x3"], "bounds": [[-np.pi, np.pi]] * 3}


def ishigami(x, a=7.0, b=0.1):
    return np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2 + b * x[:, 2] ** 4 * np.sin(x[:, 0])


def exact_ishigami_indices(a=7.0, b=0.1):
    """S1 and ST of the Ishigami function (Sobol' & Levitan 1999): V = a²/8 + bπ⁴/5 +
    b²π⁸/18 + 1/2, V1 = (1 + bπ⁴/5)²/2, V2 = a²/8, V13 = b²π⁸(1/18 − 1/50)."""
    v = a**2 / 8 + b * np.pi**4 / 5 + b**2 * np.pi**8 / 18 + 0.5
    v1, v2, v13 = 0.5 * (1 + b * np.pi**4 / 5) ** 2, a**2 / 8, b**2 * np.pi**8 * (1 / 18 - 1 / 50)
    return np.array([v1, v2, 0.0]) / v, np.array([v1 + v13, v2, v13]) / v


def test_the_ishigami_functions_sobol_indices_lie_within_their_intervals():
    s1, st = exact_ishigami_indices()
    covered, checks, informative = 0, 0, True
    for seed in range(20):
        x = design_samples(ISHIGAMI, 1024, "sobol", seed=seed)
        table, skipped = indices(ISHIGAMI, x, {"y": ishigami(x)}, "sobol", seed=seed)
        assert not skipped and list(table.parameter) == ["x1", "x2", "x3"]
        for key, exact in (("S1", s1), ("ST", st)):
            covered += int((np.abs(table[key] - exact) <= table[key + "_conf"]).sum())
            checks += 3
            # Informative, not merely wide: every index that is not 0 is told from 0.
            low = (table[key] - table[key + "_conf"])[exact > 0]
            informative &= bool((low > 0).all())
    # Nominal 95 %; measured 120 of 120 (SALib's scrambled Sobol' design makes its bootstrap
    # intervals conservative).
    assert covered >= 0.95 * checks, f"{covered} of {checks}"
    assert informative
    again = indices(ISHIGAMI, x, {"y": ishigami(x)}, "sobol", seed=19)[0]
    assert again.equals(table), "the same seed gives the same intervals"


def test_an_output_with_missing_values_is_skipped_and_said_so():
    x = design_samples(ISHIGAMI, 8, "sobol")
    y = ishigami(x)
    y[3] = np.nan
    table, skipped = indices(ISHIGAMI, x, {"y": y, "z": ishigami(x)}, "sobol")
    assert set(table.output) == {"z"} and skipped == {"y": f"1 of {len(y)} samples have no value"}
    table, skipped = indices(ISHIGAMI, x, {"y": y}, "sobol", missing="mean")
    assert not skipped and (table.imputed == 1).all() and table.S1.notna().all()
    with pytest.raises(ValueError, match="expected 'skip' or 'mean'"):
        indices(ISHIGAMI, x, {"y": y}, "sobol", missing="zero")
    with pytest.raises(ValueError, match="expected 'sobol' or 'morris'"):
        design_samples(ISHIGAMI, 8, "fast")


def test_a_small_study_of_the_thesis_runs_end_to_end_and_reruns_nothing(tmp_path, thesis, capsys):
    scenario = hagfish.Scenario.load(thesis, time_step_s=0.02)
    problem = {"names": ["drag.quadratic_g_per_cm3"], "bounds": [[0.6, 1.2]]}
    with ThreadPoolExecutor(2) as pool:
        result = hagfish.sensitivity(scenario, problem, out=tmp_path, samples=2, executor=pool,
                                     progress=False)
    # Saltelli's design: N (D + 2) = 6 samples, one run each.
    assert len(result.samples) == 6
    assert (result.samples["drag.quadratic_g_per_cm3"].between(0.6, 1.2)).all()
    assert set(result.indices.output) | set(result.skipped) == set(hagfish.sensitivities.OUTPUTS)
    assert (tmp_path / "sensitivity.csv").exists() and (tmp_path / "samples.csv").exists()
    travel = result.samples.core_travel_L
    assert travel.notna().all() and (travel > 0).any()
    capsys.readouterr()
    again = hagfish.sensitivity(scenario, problem, out=tmp_path, samples=2)
    assert again.samples.equals(result.samples)
    assert capsys.readouterr().err.count("already completed") == 6


def test_morris_gives_a_linear_functions_coefficients_exactly():
    """Elementary effects of y = 3x₁ − x₂ + 0·x₃ on [0, 1]³ are the coefficients, whatever
    the trajectory: μ* = |aᵢ|, σ = 0."""
    problem = {"names": ["a", "b", "c"], "bounds": [[0.0, 1.0]] * 3}
    x = design_samples(problem, 10, "morris", seed=3)
    assert x.shape == (10 * 4, 3)
    table, skipped = indices(problem, x, {"y": 3 * x[:, 0] - x[:, 1]}, "morris", seed=3)
    assert not skipped
    np.testing.assert_allclose(table.mu_star, [3.0, 1.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(table.sigma, [0.0, 0.0, 0.0], atol=1e-12)
