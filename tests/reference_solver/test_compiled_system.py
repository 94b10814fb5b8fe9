"""The compiled constraints of forward dynamics against the plain path (to 1e-12 on random states)
and against finite differences, and whole simulations on both paths."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.compiled_system import CompiledSystem, constraint_system
from reference_solver.dynamics import simulate
from reference_solver.system import ConstraintSystem
from scenarios import load

DYNAMIC = ["four_bar_gravity", "andrews_squeezer", "n_four_bar", "slider_crank_spring", "compound_pendulum"]


@pytest.mark.parametrize("name", DYNAMIC)
def test_compiled_rows_are_the_plain_rows_on_random_states(name: str) -> None:
    scenario = load(name)
    compiled, plain = constraint_system(scenario), ConstraintSystem(scenario)
    assert isinstance(compiled, CompiledSystem)
    rng = np.random.default_rng(7)
    for _ in range(40):
        q, qd, t = rng.normal(size=plain.unknowns), rng.normal(size=plain.unknowns), float(rng.uniform(0, 2))
        for mine, theirs in zip(compiled.evaluate(q, t, qd), plain.evaluate(q, t, qd), strict=True):
            np.testing.assert_allclose(mine, theirs, rtol=0, atol=1e-12 * max(1.0, np.max(np.abs(theirs))))
        np.testing.assert_allclose(compiled.c_t(t), plain.c_t(t), rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", DYNAMIC)
def test_compiled_jacobian_is_the_derivative_of_the_compiled_rows(name: str) -> None:
    """Central differences, step 1e-6: agreement to 1e-7 of the largest entry."""
    compiled = constraint_system(load(name))
    rng = np.random.default_rng(3)
    h = 1e-6
    for _ in range(10):
        q, t = rng.normal(size=compiled.unknowns), float(rng.uniform(0, 2))
        jac = compiled.jacobian(q, t)
        columns = [
            (compiled.residual(q + h * e, t) - compiled.residual(q - h * e, t)) / (2 * h)
            for e in np.eye(q.size)
        ]
        np.testing.assert_allclose(
            np.array(columns).T, jac, rtol=0, atol=1e-7 * max(1.0, np.max(np.abs(jac)))
        )


def test_both_paths_simulate_the_same_motion() -> None:
    """four_bar_gravity over 0.3 s at rtol 1e-12: measured 1.3e-13 apart over the full second."""
    scenario = load("four_bar_gravity", {"t_end": 0.3, "steps": 30})
    compiled, plain = simulate(scenario, rtol=1e-12, compiled=True), simulate(scenario, rtol=1e-12)
    assert np.max(np.abs(compiled.q - plain.q)) < 1e-11


def test_a_cam_or_the_plain_request_gives_the_plain_system() -> None:
    assert type(constraint_system(load("four_bar_gravity"), compiled=False)) is ConstraintSystem
    assert type(constraint_system(load("cam_roller"))) is ConstraintSystem


def test_without_qd_the_rates_are_zero_as_on_the_plain_path() -> None:
    scenario = load("four_bar_gravity")
    compiled, plain = constraint_system(scenario), ConstraintSystem(scenario)
    q = np.random.default_rng(2).normal(size=plain.unknowns)
    for mine, theirs in zip(compiled.evaluate(q, 0.4), plain.evaluate(q, 0.4), strict=True):
        np.testing.assert_allclose(mine, theirs, rtol=0, atol=1e-12 * max(1.0, np.max(np.abs(theirs))))


def test_without_usable_kernels_the_plain_system_runs_and_says_why(monkeypatch: pytest.MonkeyPatch) -> None:
    import reference_solver.compiled_system as module

    monkeypatch.setattr(module, "dense_kernels", lambda: (None, "no cache here"))
    with pytest.warns(
        RuntimeWarning, match=r"^native dynamics: the plain path runs, no cache here$"
    ) as caught:
        system = constraint_system(load("four_bar_gravity"))
    assert type(system) is ConstraintSystem and system.size > 0
    assert caught[0].filename == __file__  # stacklevel 2: the caller's line


def test_a_scenario_with_no_constraint_gets_the_plain_system() -> None:
    """A free body: no rows, nothing to compile (NotCompiled), the plain system of size 0."""
    from scenarios.bodies import Body
    from scenarios.scenario import Scenario

    free = Scenario("free", "default", (Body("puck", (0.0, 0.0, 0.0)),), (), (), 1.0, 10, 0.1)
    system = constraint_system(free)
    assert type(system) is ConstraintSystem and system.size == 0 and system.scenario is free
