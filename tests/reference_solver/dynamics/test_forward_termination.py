"""Forward dynamics (dynamics.forward) ends: a partitioned loop must never re-integrate with no
output left, repartition from the same state, or walk the integrator's steps without advancing. Each
is held here by a count, not a clock: the partitions made are counted (a spy on partitioned_ode that
refuses more than the scene needs), and the walk through the integrator's steps is read through a
bound of its length, so such a defect fails at once instead of running for ever."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from reference_solver.dynamics import forward
from reference_solver.dynamics.forward import simulate
from reference_solver.errors import AssemblyError
from reference_solver.system import ConstraintSystem
from scenarios import GROUND, Point, Revolute
from tests.support.forward_scenes import FRACTION, RTOL, nearest_turn, rod, swinging_four_bar, thrown_rod


class TooManyPartitions(RuntimeError):
    """More partitions than the scene makes: the partitioned loop does not end."""


def _budgeted(monkeypatch: pytest.MonkeyPatch, budget: int) -> list[bytes]:
    """partitioned_ode counted, refused beyond `budget` calls; the positions each partition starts
    from (their bytes)."""
    make = forward.partitioned_ode
    starts: list[bytes] = []

    def counted(system, mass, loads, q, independent):  # type: ignore[no-untyped-def]
        if len(starts) == budget:
            raise TooManyPartitions(f"partition {budget + 1} asked for")
        starts.append(np.asarray(q, dtype=float).tobytes())
        return make(system, mass, loads, q, independent)

    monkeypatch.setattr(forward, "partitioned_ode", counted)
    return starts


def test_a_scene_that_keeps_its_partition_is_integrated_once_to_the_end(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The rod pinned at its end keeps its angle as the independent coordinate all the way (its
    dependent block is regular everywhere): one partition, one integration, every grid time output."""
    made = _budgeted(monkeypatch, 1)
    scenario = rod(t_end=0.5, steps=5)
    result = simulate(scenario, rtol=1e-9)
    assert result.partitions == len(made) == 1
    np.testing.assert_array_equal(result.times, scenario.times())
    assert len(result.q) == 6


def test_repartitions_end_at_the_end_of_the_grid(monkeypatch: pytest.MonkeyPatch) -> None:
    """The swinging four-bar at REPARTITION = 0.95 is partitioned anew 9 times (measured; see
    test_forward_repartition.py): at most twice that many, each new one from a new state, and every grid
    time output once."""
    monkeypatch.setattr(forward, "REPARTITION", FRACTION)
    made = _budgeted(monkeypatch, 20)
    scenario = swinging_four_bar()
    result = simulate(scenario, rtol=RTOL)
    assert 5 <= result.partitions == len(made) <= 20
    assert len(set(made)) == len(made)  # no partition made twice from the same state
    np.testing.assert_array_equal(result.times, scenario.times())


def test_the_walk_visits_each_integrator_step_before_each_output_once() -> None:
    """forward._walk on a real dense solution (y' = -y on [0, 1]): the integrator's steps before each
    output time, in order, each once (flagged False, its own state), then the output (flagged True,
    the dense solution there); steps after the last output are not walked. Read through a bound one
    longer than that sequence, so a walk that repeats a step cannot run for ever here."""
    sol = solve_ivp(lambda t, y: -y, (0.0, 1.0), [1.0], rtol=1e-6, dense_output=True)
    assert len(sol.t) >= 6  # steps between the outputs
    outputs = np.array([0.05, 0.3, 0.31, 0.7])
    expected: list[tuple[float, bool]] = []
    step = 0
    for time in outputs:
        while sol.t[step] < time:
            expected.append((float(sol.t[step]), False))
            step += 1
        expected.append((float(time), True))
    walked = list(itertools.islice(forward._walk(sol, outputs), len(expected) + 1))
    assert [(t, flag) for t, _, flag in walked] == expected
    for t, y, flag in walked:
        np.testing.assert_array_equal(y, sol.sol(t) if flag else sol.y[:, list(sol.t).index(t)])


@pytest.mark.parametrize("apart", [3.0, 0.1, 1e-10])
def test_a_mechanism_that_cannot_assemble_is_refused_with_its_miss(apart: float) -> None:
    """The rod's end pinned at the origin and at (d, 0) at once: least squares puts it half way, each
    x row missing by d / 2 over L = 0.5, so d = 3 misses by 3 lengths, and d = 0.1 and 1e-10 miss by
    0.1 and 1e-10 of the length, above assemble_free's 1e-12 and below one length: all refused."""
    second = Revolute("second", Point(GROUND, (apart, 0.0)), Point("link_1", (-0.25, 0.0)))
    scenario = rod(joints=(*rod().joints, second))
    with pytest.raises(AssemblyError) as caught:
        simulate(scenario)
    message = str(caught.value)
    prefix = "compound_pendulum: the mechanism cannot assemble at t=0: the constraints miss by "
    assert message.startswith(prefix) and message.endswith(" (relative to the characteristic length)")
    assert float(message[len(prefix) :].split()[0]) == pytest.approx(apart, rel=1e-3)
    # the error carries the least-squares configuration it measured
    system = ConstraintSystem(scenario)
    assert caught.value.q is not None and caught.value.time == 0.0
    miss = np.max(np.abs(system.residual(caught.value.q, 0.0) / system.row_scales))
    assert miss == pytest.approx(apart, rel=1e-3)


def test_a_thrown_rod_starts_with_the_centripetal_acceleration_of_its_rates() -> None:
    """test_forward.py's rod given rates (0.7, -0.4, 3): its centre, at r = pin + (l / 2)(cos, sin)
    of theta, turns at the omega test_forward.py derives, so its acceleration is theta'' a - omega^2
    (l / 2)(cos, sin) with a = (l / 2)(-sin, cos): the velocity terms of C_q q'' = Q_d at the start
    (theta'' about the pin does not see omega)."""
    body, start, theta = thrown_rod()
    radial = 0.25 * np.array([math.cos(theta), math.sin(theta)])
    a, omega = nearest_turn(body, theta)
    assert abs(omega) > 1.0
    expected = start.qdd[2] * a - omega**2 * radial
    np.testing.assert_allclose(start.qdd[:2], expected, rtol=0, atol=1e-12 * np.max(np.abs(expected)))
