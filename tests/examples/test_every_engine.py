"""Every example file on every engine at its default setting, against the example's closed form.

Each supported (example, engine) pair must stay within the engine's bound below: the dimensionless
error per level (reports.harness.level_error: lengths over L, rates over L w, accelerations over
L w^2), measured once (2026-11-23, this machine) and given a margin of about ten. Each pair an
engine does not support must say so with the reason listed here. The slider-crank and the
straight-line linkage run in the default suite; the other examples are marked slow.

Measured worst over the kinematic examples (position, velocity, acceleration):
    reference   5.6e-15  1.6e-15  4.9e-15   (Newton at 1e-12 on the closed forms' rounding)
    pinocchio   6.4e-15  2.2e-15  4.8e-15   (its kinematic mode: Newton on Pinocchio's kinematics)
    mujoco      1.4e-07  2.5e-05  7.1e-03   (RK4 dt 1e-4 on soft equality constraints; the
                                            spline cam and the polynomial drive on their own)
    exudyn      5.6e-15  5.0e-06  2.1e-02   (GA3: positions on the constraints, rates integrated)
and the dynamic example (damped_oscillators), forward dynamics at each engine's default:
    reference   1.5e-12  2.2e-12  1.4e-11   (DOP853 rtol 1e-12)
    mujoco      9.2e-13  2.9e-12  9.3e-12   (RK4 dt 3e-4)
    exudyn      1.2e-05  4.0e-05  1.3e-04   (GA3 dt 1e-3: second order, with numerical damping)
"""

from __future__ import annotations

import math

import pytest

import adapters
from tests.examples.closed_forms import CLOSED_FORMS
from tests.examples.engine_errors import default_run, errors
from tests.examples.support import example

ENGINES = ("reference", "mujoco", "exudyn", "pinocchio")
BOUNDS: dict[str, tuple[float, float, float]] = {
    "reference": (5e-14, 2e-14, 5e-14),
    "pinocchio": (5e-14, 2e-14, 5e-14),
    "mujoco": (1e-6, 2e-4, 7e-2),
    "exudyn": (5e-14, 5e-5, 2e-1),
}
DYNAMIC_BOUNDS: dict[str, tuple[float, float, float]] = {
    "reference": (1e-11, 2e-11, 1e-10),
    "mujoco": (1e-11, 3e-11, 1e-10),
    "exudyn": (1e-4, 3e-4, 1e-3),
    "pinocchio": (3e-9, 1e-8, 3e-8),  # measured 3.0e-10, 9.5e-10, 3.0e-9 (baumgarte, dt 1.25e-3)
}
OFF_LATTICE: dict[tuple[str, str], tuple[float, float, float]] = {
    ("exudyn", "peaucellier_lipkin"): (3e-9, 5e-5, 2e-1),  # measured 7.1e-10, 2.4e-6, 8.1e-4
}
"""Where the example's output times fall between the engine's steps (docs/settings-rule.md: the grid
never sets the step), Exudyn's positions there are interpolated from the two steps around them, no
longer on the constraints to round-off."""
POLYCOEF: dict[tuple[str, str], tuple[float, float, float]] = {
    ("mujoco", "slider_crank_polynomial"): (1.1e-4, 1.6e-4, 1.7e-3),  # measured 3.7e-5, 5.2e-5, 5.5e-4
}
"""MuJoCo carries a polynomial drive by its joint equality's polycoef, whose dJ/dt v term it leaves
out: the crank lags by about P''(t) tc^2 (adapters.mujoco.adapter; with `polynomial=steered`
2.0e-7, 4.4e-6, 5.2e-4, and its kinematic mode 3.1e-15, 4.5e-14, 3.3e-14)."""
FACETED: dict[tuple[str, str], tuple[float, float, float]] = {
    ("mujoco", "cam_roller_spline"): (2.5e-4, 1.5e-2, 9.0),  # measured 7.7e-5, 4.8e-3, 2.9
}
"""MuJoCo's model of a spline cam is a polygon of facets (512 by default): the roller's contact
kinks at each vertex (tests/examples/test_spline_cam.py: the errors fall with the piece count)."""
UNSUPPORTED: dict[tuple[str, str], str] = {}
"""(engine, example) pairs an engine refuses, with the words its reason must contain."""
FAST = ("slider_crank", "slider_crank_polynomial", "watt_straight_line")
LEVELS = ("position", "velocity", "acceleration")


def _cases() -> list[object]:
    cases = []
    for name in CLOSED_FORMS:
        for engine in ENGINES:
            marks = [] if name in FAST else [pytest.mark.slow]
            cases.append(pytest.param(name, engine, marks=marks, id=f"{name}-{engine}"))
    return cases


def test_every_example_has_a_closed_form() -> None:
    from tests.examples.support import EXAMPLES

    assert {p.stem for p in EXAMPLES.glob("*.toml")} == set(CLOSED_FORMS)


@pytest.mark.parametrize(("name", "engine"), _cases())
def test_example_on_engine(name: str, engine: str) -> None:
    adapter = adapters.load(engine)  # the engines are hard dependencies: a missing one fails here
    scenario = example(name)
    reason, expected_reason = adapter.supports(scenario), UNSUPPORTED.get((engine, name))
    result = default_run(engine, scenario) if reason is None else None
    if expected_reason is not None:  # said by supports(), or by the run's status
        said = reason if result is None else f"{result.status}: {result.message}"
        assert result is None or result.status == "unsupported", said
        assert expected_reason in said, said
        return
    assert result is not None, f"{engine} refuses {name}: {reason}"
    assert result.status == "ok" and result.trajectory is not None, result.message
    found = errors(name, scenario, result.trajectory)
    bounds = (
        OFF_LATTICE.get((engine, name))
        or POLYCOEF.get((engine, name))
        or FACETED.get((engine, name))
        or (DYNAMIC_BOUNDS if scenario.analysis == "dynamic" else BOUNDS)[engine]
    )
    for level, bound in zip(LEVELS, bounds, strict=True):
        assert not math.isnan(found[level]), f"{engine} gives no {level} for {name}"
        assert found[level] < bound, (level, found[level], bound)
