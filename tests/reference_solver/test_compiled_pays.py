"""Where the compiled path pays (reference_solver.compiled.pays): in a process that weighs the work
(`mbxval solve`, compiled.compile_where_it_pays) a solve of a few points runs the plain path rather than
load numba and its kernels, a long one or one in a process that holds the kernels runs the compiled
path; a process that does not weigh it (a harness) always runs the compiled path; and the two give
the same kinematics, forces and residual. The choice itself is checked in a fresh interpreter by
the modules it imports (tests/reports/cli/test_imports_on_demand.py)."""

from __future__ import annotations

import numpy as np
import pytest

import reference_solver.compiled as compiled
from reference_solver import analyse, constraint_residual
from reference_solver.dynamics.inverse import inverse_dynamics
from scenarios import load


@pytest.fixture
def weighing(monkeypatch: pytest.MonkeyPatch) -> None:
    """This process weighs the work, and holds no kernels yet (as far as `pays` knows)."""
    monkeypatch.setattr(compiled, "_by_work", True)
    monkeypatch.setattr(compiled, "_loaded", set())


def test_a_process_that_does_not_weigh_the_work_always_compiles(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(compiled, "_by_work", False)
    monkeypatch.setattr(compiled, "_loaded", set())
    assert compiled.pays("path", 9, 2, None) and not compiled.pays("path", 9, 2, False)


def test_an_explicit_choice_decides(weighing: None) -> None:
    assert compiled.pays("path", 1, 1, True) and not compiled.pays("path", 10**6, 10**6, False)


def test_none_chooses_by_the_work_where_the_kernels_are_not_loaded(weighing: None) -> None:
    assert not compiled.pays("path", 9, 2, None)
    assert not compiled.pays("path", 9, compiled.PAYS_FROM // 9, None)  # 4,995 row-steps
    assert compiled.pays("path", 9, compiled.PAYS_FROM // 9 + 1, None)  # 5,004


def test_none_takes_kernels_already_loaded_whatever_the_work(
    weighing: None, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(compiled, "_loaded", {"residuals"})
    assert compiled.pays("residuals", 9, 2, None) and not compiled.pays("path", 9, 2, None)


@pytest.mark.parametrize("name", ["four_bar", "slider_crank", "cam_roller", "planetary_gears"])
def test_both_paths_give_the_same_kinematics_forces_and_residual(name: str) -> None:
    """On a grid of 5 points each result of `None` (the plain path here, where nothing is loaded)
    equals the compiled one: positions to 1e-12 of the length scale, rates and forces to 1e-9 of
    their largest (the same Newton iterations in another order of operations)."""
    scenario = load(name)
    grid = np.asarray(scenario.times(steps=4))
    compiled, chosen = analyse(scenario, grid, compiled=True), analyse(scenario, grid, compiled=False)
    scale = scenario.characteristic_length
    np.testing.assert_allclose(chosen.q, compiled.q, rtol=0, atol=1e-12 * max(1.0, scale))
    for plain, fast_level in ((chosen.qd, compiled.qd), (chosen.qdd, compiled.qdd)):
        np.testing.assert_allclose(plain, fast_level, rtol=0, atol=1e-9 * max(1.0, np.abs(fast_level).max()))
    if all(body.mass > 0 for body in scenario.bodies):
        forces, plain_forces = (
            inverse_dynamics(scenario, compiled, True),
            inverse_dynamics(scenario, compiled, False),
        )
        assert forces.keys() == plain_forces.keys()
        for key, values in forces.items():
            top = max(1.0, float(np.abs(values).max()))
            np.testing.assert_allclose(plain_forces[key], values, rtol=0, atol=1e-9 * top, err_msg=key)
    trajectory = compiled.trajectory()
    residual, plain_residual = (
        constraint_residual(scenario, trajectory, True),
        constraint_residual(scenario, trajectory, False),
    )
    np.testing.assert_allclose(plain_residual, residual, rtol=0, atol=1e-13)


def test_a_small_solve_by_none_is_the_plain_paths_result(
    weighing: None, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With nothing loaded, `compiled=None` on two points is the plain path's result to the bit, and
    with the kernels loaded it is the compiled path's."""
    scenario = load("four_bar")
    grid = np.asarray(scenario.times(steps=1))
    np.testing.assert_array_equal(
        analyse(scenario, grid, compiled=None).q, analyse(scenario, grid, compiled=False).q
    )
    monkeypatch.setattr(compiled, "_loaded", {"path"})
    np.testing.assert_array_equal(
        analyse(scenario, grid, compiled=None).q, analyse(scenario, grid, compiled=True).q
    )
