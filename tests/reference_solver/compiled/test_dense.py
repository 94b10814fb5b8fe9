"""The dense kernels (compiled.dense through CompiledSystem) on driven mechanisms: C_t against the drivers'
motion laws differentiated by hand, and C, C_q, Q_d at the hand-worked motion of test_analysis.py's
crank. The dynamics scenarios of test_compiled_system.py have no driver, so there C_t is zero and C
does not depend on the time whatever the kernels do with it."""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios
from reference_solver.compiled_system import CompiledSystem, constraint_system
from reference_solver.system import ConstraintSystem
from tests.support.hand_crank import AMPLITUDE, OMEGA, crank_by_hand, crank_scenario


@pytest.mark.parametrize("t", [0.0, 0.3, 1.7])
def test_a_harmonic_driver_s_c_t_is_minus_its_rate(t: float) -> None:
    """The crank of test_analysis.py: C = (pin x, pin y, theta - m - A cos(w t)), so C_t = (0, 0,
    -f'(t)) = (0, 0, A w sin(w t))."""
    system = constraint_system(crank_scenario())
    assert isinstance(system, CompiledSystem)
    expected = [0.0, 0.0, AMPLITUDE * OMEGA * math.sin(OMEGA * t)]
    np.testing.assert_allclose(system.c_t(t), expected, rtol=0, atol=1e-15)


def test_a_driver_at_constant_speed_has_a_constant_c_t() -> None:
    """The four-bar's crank turns at a constant rate w: its driver row's C_t is -w at any time, every
    joint row's 0."""
    scenario = scenarios.build("four_bar")
    system = constraint_system(scenario)
    assert isinstance(system, CompiledSystem)
    (driver,) = scenario.drivers
    rate = driver.motion.rate  # type: ignore[attr-defined]
    assert rate != 0.0
    for t in (0.0, 0.25, 3.0):
        c_t = system.c_t(t)
        np.testing.assert_array_equal(c_t[:-1], 0.0)
        assert c_t[-1] == -rate


@pytest.mark.parametrize("t", [0.3, 1.7])
def test_the_hand_worked_motion_satisfies_the_compiled_equations_at_its_time(t: float) -> None:
    """At the crank's hand-worked q, q', q'' of time t: C = 0, C_q q' = -C_t and C_q q'' = Q_d, with C,
    C_q and Q_d from the compiled evaluation at (q, q', t), whose driver row reads the time."""
    system = constraint_system(crank_scenario())
    q, qd, qdd = (level[0] for level in crank_by_hand(np.array([t])))
    c, c_q, q_d = system.evaluate(q, t, qd)
    np.testing.assert_allclose(c, 0.0, rtol=0, atol=1e-15)
    np.testing.assert_allclose(c_q @ qd, -system.c_t(t), rtol=0, atol=1e-14)
    np.testing.assert_allclose(c_q @ qdd, q_d, rtol=0, atol=1e-13)
    assert abs(q_d[-1]) > 1.0  # the driver's f'' = -A w^2 cos(w t), not zero at these times


def test_a_mechanism_of_more_bodies_than_a_row_s_slots_evaluates_as_the_plain_one() -> None:
    """The N-four-bar with 6 loops has 13 bodies, more than a row's WIDTH = 10 slots: the kernels'
    scratch holds a cosine and sine per body, and its C, C_q, Q_d and C_t at random states are the
    plain system's."""
    scenario = scenarios.build("n_four_bar", overrides={"loops": 6})
    compiled, plain = constraint_system(scenario), ConstraintSystem(scenario)
    assert isinstance(compiled, CompiledSystem) and len(scenario.bodies) == 13
    rng = np.random.default_rng(29)
    for _ in range(3):
        q, qd, t = rng.normal(size=plain.unknowns), rng.normal(size=plain.unknowns), float(rng.uniform(0, 2))
        for mine, theirs in zip(compiled.evaluate(q, t, qd), plain.evaluate(q, t, qd), strict=True):
            np.testing.assert_allclose(mine, theirs, rtol=0, atol=1e-12 * max(1.0, np.max(np.abs(theirs))))
