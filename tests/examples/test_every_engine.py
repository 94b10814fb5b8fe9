"""Every example file on every engine at its default setting, against the example's closed form.

Each supported (example, engine) pair must stay within a factor 3 of its measured error, either
way (MEASURED below: the dimensionless error per level of reports.scoring.level_error: lengths
over L, rates over L w, accelerations over L w^2; round-off held from above only). Each pair an
engine does not support must say so with the reason listed here. The slider-crank, its polynomial
drive and the straight-line linkage run in the quick loop; the other examples are marked slow.

The worst over the kinematic examples: the native solver and Pinocchio's kinematic mode at
round-off (Newton on the closed forms' rounding); MuJoCo 8.1e-11 / 1.5e-10 / 7.9e-10 (RK4 at the
settings rule's step on soft equality constraints, their time constant 128 steps with the
regulariser scaled at compile time, adapters.mujoco.weights; its faceted spline cam on its own
below); Exudyn 5.6e-15 / 7.1e-6 / 1.8e-3 (GA3
after its run-in: positions on the constraints, rates integrated, second order; the spline cam's
accelerations restart generalized-alpha's transient at each knot; before the run-in the start-up
transient gave 2.1e-2). The
dynamic example (damped_oscillators) at each engine's default: native 1.4e-11 (DOP853 rtol 1e-12),
MuJoCo round-off, Pinocchio 5.0e-11, Exudyn 6.3e-6 (GA3, second order with numerical damping).
"""

from __future__ import annotations

import math

import pytest

import adapters
from tests.support.bounds import held
from tests.support.engines import ENGINES
from tests.support.examples.closed_forms import CLOSED_FORMS
from tests.support.examples.engine_errors import default_run, errors
from tests.support.examples.files import example
from tests.support.measured import measured_table

MEASURED: dict[tuple[str, str], tuple[float, ...]] = measured_table("every_engine_on_the_examples")
"""(example, engine): its (position, velocity, acceleration) error at the engine's default, measured
on this kind of machine (mujoco 4.0.0, exudyn 1.13.6,
pin 4.1.0) and held two-sided (tests.support.bounds). Exudyn's positions on peaucellier_lipkin were
interpolated (7.1e-10) until Exudyn's step was shortened to put the example's outputs on its steps
(adapters.lattice.outputs_on_steps). MuJoCo
drives slider_crank_polynomial's quartic by its steered clock (through a joint equality's polycoef
the crank would lag by about P''(t) tc^2 at the default's 128-step time constant). Its
model of cam_roller_spline's profile is a polygon of 512 facets: the roller's contact kinks at
each vertex (tests/examples/test_spline_cam.py: the errors fall with the piece count). Drake
(1.51.1): SAP at the rule's step, positions a_max h^2 (adapters.drake)."""
UNSUPPORTED: dict[tuple[str, str], str] = {
    ("drake", "cam_roller_spline"): "no cam joint",
}
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
    from tests.support.examples.files import EXAMPLES

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
    for level in LEVELS:
        assert not math.isnan(found[level]), f"{engine} gives no {level} for {name}"
    held([found[level] for level in LEVELS], MEASURED[(name, engine)])
