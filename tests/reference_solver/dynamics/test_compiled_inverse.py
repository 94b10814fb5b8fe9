"""The compiled inverse dynamics (dynamics.compiled_inverse, compiled.inverse_kernel) against the plain
loop (dynamics.inverse with compiled=False: plain rows, plain loads, scipy's lstsq) to 1e-12 on
random states: every driver force, reaction and energy, at states that need not satisfy anything
(the multipliers are the least-squares solution of C_q^T lambda = Q_e - M q'' at any state)."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.compiled_system import CompiledSystem, constraint_system
from reference_solver.dynamics import inverse_dynamics
from reference_solver.dynamics.compiled_inverse import compiled_outputs
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.layout import Layout
from reference_solver.solution import Analysis

SCENES = [
    "slider_crank",  # drivers and joints, no loads
    "four_bar_chain",  # many loops
    "planetary_gears",  # gear rows
    "rack_pinion",
    "andrews_squeezer",  # springs and a torque
    "slider_crank_spring",  # a spring-damper
    "compound_pendulum",  # gravity
]


def _random_analysis(scenario: scenarios.Scenario, seed: int, count: int = 7) -> Analysis:
    layout = Layout.of(scenario)
    rng = np.random.default_rng(seed)
    start = layout.initial_guess(scenario)
    q = start + rng.normal(scale=0.3, size=(count, layout.size)) * np.maximum(1.0, np.abs(start))
    qd, qdd = rng.normal(size=(2, count, layout.size)) * 5.0
    times = np.sort(rng.uniform(0.0, scenario.t_end, count))
    zeros = np.zeros(count)
    return Analysis(layout, times, q, qd, qdd, zeros.astype(int), zeros, zeros)


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("seed", [1, 2])
def test_the_compiled_inverse_dynamics_is_the_plain_loop_s(name: str, seed: int) -> None:
    scenario = scenarios.build(name)
    analysis = _random_analysis(scenario, seed)
    system = constraint_system(scenario)
    assert isinstance(system, CompiledSystem)
    mass = mass_diagonal(scenario, system.layout, massless_contacts=True)
    compiled = compiled_outputs(system, mass, Loads(scenario, system.layout, mass), analysis)
    assert compiled is not None  # these scenes compile: the kernel, not the fallback, is checked
    plain = inverse_dynamics(scenario, analysis, compiled=False)
    assert list(compiled) == list(plain)  # the same columns in the same order
    scale = max(float(np.max(np.abs(v))) for v in plain.values())
    for key, value in plain.items():
        np.testing.assert_allclose(compiled[key], value, rtol=1e-12, atol=1e-12 * scale, err_msg=key)
    assert np.array_equal(inverse_dynamics(scenario, analysis)["energy.kinetic"], compiled["energy.kinetic"])


def test_a_scene_with_cams_keeps_the_plain_loop() -> None:
    scenario = scenarios.build("cam_roller", overrides={"steps": 4})
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout, massless_contacts=True)
    analysis = _random_analysis(scenario, 3)
    assert compiled_outputs(system, mass, Loads(scenario, system.layout, mass), analysis) is None
    assert set(inverse_dynamics(scenario, analysis)) == set(
        inverse_dynamics(scenario, analysis, compiled=False)
    )
