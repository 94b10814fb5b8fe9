"""Pinocchio's kinematic mode never jumps to another assembly branch silently.

After Newton converges, its solution must lie near the step's predictor (within half the
predictor's own move plus 1e-6, in unknown sizes); farther, the step is halved, and a jump that
persists is reported as `singular` with its time. On the undercut cam (a lobed cam whose valleys
nearly fit the roller), the solver without this guard landed on another contact point at t = 0.474
(error 2.0); with it, it follows the branch (measured error 2.8e-15). On the catalogue's regular
scenarios the guard never fires: the largest ratio measured is 0.008 of the allowed distance.
"""

from __future__ import annotations

import numpy as np
import pytest

import adapters.pinocchio.kinematics as kinematics
import reference_solver
import scenarios
from adapters.pinocchio import PinocchioAdapter
from scenarios import Scenario
from scenarios.trajectory import Trajectory

UNDERCUT = "cam_roller/stress_undercut"
REFINE = 8


def truth(scenario: Scenario, times: np.ndarray) -> Trajectory:
    """The reference solution on a grid REFINE times finer, on which it follows the branch."""
    fine = np.linspace(times[0], times[-1], REFINE * (times.size - 1) + 1)
    solved = reference_solver.solve(scenario, fine, tolerance=1e-12)
    assert solved.position is not None
    return Trajectory(times, solved.bodies, solved.position[::REFINE])


def position_errors(scenario: Scenario, result: Trajectory) -> np.ndarray:
    """The largest position error at each grid time."""
    reference = truth(scenario, result.times).select(result.bodies)
    assert result.position is not None and reference.position is not None
    return np.abs(result.position - reference.position).max(axis=(1, 2))


def test_the_undercut_cam_is_followed_on_its_own_grid() -> None:
    scenario = scenarios.build(UNDERCUT)
    result = PinocchioAdapter().run(scenario)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    assert position_errors(scenario, result.trajectory).max() < 1e-12


def test_with_one_halving_the_guard_reports_where_the_solver_would_jump(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    scenario = scenarios.build(UNDERCUT)
    monkeypatch.setattr(kinematics, "HALVINGS", 1)
    monkeypatch.setattr(kinematics, "JUMP", np.inf)  # the guard off: the solver jumps silently
    unguarded = PinocchioAdapter().run(scenario)
    # Without the guard the solver either jumps to the other closure silently or, depending on the
    # rounding of the last iterations, stalls there; either way the trouble starts at one time.
    if unguarded.status == "ok":
        assert unguarded.trajectory is not None
        errors = position_errors(scenario, unguarded.trajectory)
        assert errors.max() > 0.01
        trouble = float(unguarded.trajectory.times[np.argmax(errors > 1e-6)])
        lead = 1  # the guard stops within the step the jump happens in
    else:
        assert unguarded.status == "failed" and unguarded.failure_time is not None, unguarded.message
        trouble = unguarded.failure_time
        lead = 5  # a stall shows a few steps after the iterates have left the branch
    monkeypatch.setattr(kinematics, "JUMP", 0.5)
    guarded = PinocchioAdapter().run(scenario)
    assert guarded.status == "singular"
    assert "farther from the predictor" in guarded.message
    assert guarded.failure_time is not None
    assert trouble - lead * scenario.t_end / scenario.steps <= guarded.failure_time <= trouble


def test_the_guard_stays_quiet_on_the_regular_scenarios(monkeypatch: pytest.MonkeyPatch) -> None:
    ratios: list[float] = []
    measure = kinematics.KinematicSolver.jump

    def recorded(self: kinematics.KinematicSolver, *args: np.ndarray) -> float:
        ratios.append(measure(self, *args))
        return ratios[-1]

    monkeypatch.setattr(kinematics.KinematicSolver, "jump", recorded)
    adapter = PinocchioAdapter()
    for name in scenarios.catalogue():
        result = adapter.run(scenarios.build(name))
        assert result.status == "ok", (name, result.message)
    assert len(ratios) > 1000
    assert max(ratios) < 0.1


def test_a_crossing_between_grid_points_is_bracketed_by_the_interval_halved_halvings_times() -> None:
    """Crank and rod of equal length (0.2 m), crank from 0.5 rad at 50 rad/s: the determinant of
    the Jacobian changes sign at th2 = pi / 2, t* = (pi / 2 - 0.5) / 50, between two grid points.
    Each halving keeps the half that holds t*, so after HALVINGS of them the reported time is the
    end of the sub-interval of width h / 2**HALVINGS that contains t*: t_k + ceil(f 2**HALVINGS) h /
    2**HALVINGS, with f the fraction of the output interval [t_k, t_k + h] before t*."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.5})
    times = np.asarray(scenario.times())
    h = float(times[1] - times[0])
    crossing = (np.pi / 2 - 0.5) / 50
    k = int(np.searchsorted(times, crossing)) - 1
    cells = (crossing - times[k]) / h * 2**kinematics.HALVINGS
    assert 0.01 < cells % 1.0 < 0.99  # t* well inside a cell: its end does not depend on round-off
    result = PinocchioAdapter().run(scenario)
    assert result.status == "singular" and "determinant changes sign" in result.message, result.message
    expected = times[k] + np.ceil(cells) * h / 2**kinematics.HALVINGS
    assert result.failure_time == pytest.approx(expected, abs=1e-15)
