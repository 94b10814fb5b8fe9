"""The right-hand-side replay (benchmarks.rhs_replay) measures the work the integration did: the
recorded calls, replayed through the plain and the compiled ODE, end on the same configuration,
and each call is timed."""

from __future__ import annotations

import numpy as np

import scenarios
from benchmarks.rhs_replay import Call, _odes, _recording, _replay, rhs_seconds
from reference_solver.dynamics import simulate


def test_the_replayed_calls_end_where_the_integration_did_on_both_paths() -> None:
    scenario = scenarios.build("compound_pendulum", overrides={"t_end": 0.05, "steps": 5})
    calls: list[Call] = []
    with _recording(calls):
        simulate(scenario, scenario.times(), compiled=True)
    assert sum(kind for kind, _, _ in calls) > 50 and not all(kind for kind, _, _ in calls)
    plain, compiled = _odes(scenario)
    for ode in (plain, compiled):
        assert _replay(ode, calls) > 0
    t, y = calls[-1][1], calls[-1][2]
    np.testing.assert_allclose(compiled.state(t, y).q, plain.state(t, y).q, rtol=0, atol=1e-12)


def test_rhs_seconds_gives_a_time_per_call_for_each_path() -> None:
    scenario = scenarios.build("compound_pendulum", overrides={"t_end": 0.05, "steps": 5})
    plain, compiled = rhs_seconds(scenario, scenario.times(), repeats=1, limit=100)
    assert 0 < compiled < plain < 1
