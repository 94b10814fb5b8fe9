"""The constraint residual of cam scenarios on the compiled rows (reference_solver.compiled.residuals):
the plain rows' value on every cam scenario of the default suite and on a lobed profile, at random
states (far off the constraints, with and without the contact parameter) and on the native
solution, as the harness measures it (and its contact parameter moved by 1e-6 rad); the plain rows
never run."""

from __future__ import annotations

import dataclasses
import os

import numpy as np
import pytest

import reference_solver.residual as residual_module
import scenarios
from reference_solver import analyse
from reference_solver.residual import constraint_residual, plain_constraint_residual

DEFAULT_SUITE_CAMS = [
    "cam_knife_edge",
    "cam_knife_edge/spline",
    "cam_roller",
    "cam_roller/spline",
    "cam_flat_face",
    "cam_flat_face/spline",
]
LOBED = [("cam_knife_edge", "lobed"), ("cam_roller", "lobed"), ("cam_flat_face", "lobed")]
CASES = [(name, "disc") for name in DEFAULT_SUITE_CAMS] + LOBED


def _scenario(name: str, profile: str) -> scenarios.Scenario:
    settings = {"steps": "40"} if profile == "disc" else {"steps": "40", "profile": profile}
    return scenarios.load(name, settings)


def _random(scenario: scenarios.Scenario, seed: int) -> scenarios.Trajectory:
    """Every body at a random pose (of the characteristic length's size) and the contact parameter at
    a random angle of up to two turns either way, at each time of the scenario's grid."""
    rng = np.random.default_rng(seed)
    times = np.asarray(scenario.times())
    bodies = tuple(b.name for b in scenario.bodies)
    position = rng.normal(scale=scenario.characteristic_length, size=(len(times), len(bodies), 3))
    extras = {f"{c.name}.phi": rng.uniform(-4 * np.pi, 4 * np.pi, len(times)) for c in scenario.cams}
    return scenarios.Trajectory(times, bodies, position=position, extras=extras)


@pytest.mark.parametrize(("name", "profile"), CASES)
def test_compiled_and_plain_rows_give_one_residual_at_random_states(name: str, profile: str) -> None:
    scenario = _scenario(name, profile)
    assert scenario.cams
    for seed in range(3):
        trajectory = _random(scenario, seed)
        compiled, plain = (
            constraint_residual(scenario, trajectory),
            plain_constraint_residual(scenario, trajectory),
        )
        assert np.all(plain > 1e-3)  # random states are far off the constraints
        np.testing.assert_allclose(compiled, plain, rtol=1e-13, atol=0)
        without = dataclasses.replace(trajectory, extras={})  # the cam's rows left out
        compiled, plain = constraint_residual(scenario, without), plain_constraint_residual(scenario, without)
        assert np.all(plain > 1e-3)
        np.testing.assert_allclose(compiled, plain, rtol=1e-13, atol=0)


@pytest.mark.parametrize("name", DEFAULT_SUITE_CAMS)
def test_on_the_native_solution_the_compiled_residual_is_the_plain_one(name: str) -> None:
    """The native solver's trajectory (positions and the contact parameter, as the harness measures
    it): round-off on both paths, the same to 4e-16 (measured at most 1.4e-16: the round-off of terms
    of the characteristic length's size). Its contact parameter moved by 1e-6 rad opens the contact
    by about 1e-6 R / L, R of L's size (measured 6.4e-7 to 2.0e-6 over the six), the same on both
    paths to 4e-16 again."""
    scenario = scenarios.load(name, {"steps": "40"})
    solution = analyse(scenario, np.asarray(scenario.times())).trajectory()
    (contact,) = scenario.cams
    key = f"{contact.name}.phi"
    assert set(solution.extras) >= {key}
    for shift, low, high in ((0.0, 0.0, 1e-15), (1e-6, 1e-6 / 3, 3e-6)):
        moved = dataclasses.replace(solution, extras={key: solution.extras[key] + shift})
        compiled, plain = constraint_residual(scenario, moved), plain_constraint_residual(scenario, moved)
        assert np.all(plain >= low) and np.all(plain < high)
        np.testing.assert_allclose(compiled, plain, rtol=0, atol=4e-16)


def test_a_cam_scenario_is_measured_on_its_compiled_rows(monkeypatch: pytest.MonkeyPatch) -> None:
    """Cams compile too: constraint_residual never evaluates the plain rows (about 300 times slower
    on a cam scenario's 201 points)."""

    def refused(*args: object) -> None:
        raise AssertionError("the plain rows were evaluated")

    monkeypatch.setattr(residual_module, "_plain_residual", refused)
    scenario = scenarios.load("cam_flat_face/spline", {"steps": "24"})
    solution = analyse(scenario, np.asarray(scenario.times())).trajectory()
    assert np.max(constraint_residual(scenario, solution)) < 1e-15


def test_without_usable_kernels_the_plain_rows_run_and_say_why(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where numba can cache its kernels nowhere, the residual is the plain rows' (a scenario of its
    own: the compiled rows are kept per scenario), with a warning at the caller's line."""
    monkeypatch.setattr(residual_module, "residual_kernels", lambda: (None, "no cache here"))
    scenario = scenarios.load("cam_roller", {"steps": "7", "omega": "41"})
    solution = _random(scenario, 11)
    with pytest.warns(
        RuntimeWarning, match=r"^constraint residual: the plain rows run, no cache here$"
    ) as caught:
        measured = constraint_residual(scenario, solution)
    where = caught[0].filename  # the caller's line; under mutation, mutmut's trampoline is one frame more
    assert where == __file__ or ("MUTMUT_DEPENDENCY_DEPTH" in os.environ and where.endswith("trampoline.py"))
    np.testing.assert_array_equal(measured, plain_constraint_residual(scenario, solution))
