"""Exudyn adapter: every scenario of the catalogue against its closed form (the reference solver for
spline cams), masses that do not matter, the convergence orders of the step-size ladder, honest
failures and unsupported scenarios, and runs that write no file and print nothing.

Measured with Exudyn 1.13.6, errors relative to the largest value of the level over the run (the
table MEASURED, held two-sided):
- GA3 (generalized-alpha index 3, spectral radius 0.9, the settings rule's default step, after its
  run-in): positions 1e-16..1e-15; velocities 9e-9 (cams) .. 5.6e-6 (four-bar), O(dt^2);
  accelerations 2e-6..3e-5, O(dt^2) (1e-3 on spline cams: the transient restarts at each knot,
  where the profile's third derivative jumps). Without the run-in the start-up transient of
  index-3 generalized-alpha (O(dt)) gave 1e-3..2e-2.
- STATIC (static solve per time point, velocity and acceleration solves on Exudyn's Jacobian):
  positions 5e-15, velocities 6e-15, accelerations 1e-12 (2e-5 on spline cams, whose third
  derivative jumps at the knots under the differences that give Q_d).
"""

from __future__ import annotations

import dataclasses
import math
import os
from typing import Any

import numpy as np
import pytest

import reference_solver
import scenarios
from adapters.base import Setting
from adapters.exudyn import ExudynAdapter
from adapters.exudyn.model import build_model
from adapters.step_rule import shortest_period
from scenarios import Point, RevoluteRevolute, Scenario, Trajectory
from scenarios.closed_form import exact
from scenarios.scenario import Level
from tests.support.bounds import held
from tests.support.measured import measured_table

ADAPTER = ExudynAdapter()
CATALOGUE = scenarios.catalogue()
LEVELS: tuple[Level, ...] = ("position", "velocity", "acceleration")
MODES = ("GA3", "STATIC")
MEASURED: dict[tuple[str, str], tuple[float, ...]] = measured_table("exudyn_modes")
"""(scenario, mode): (position [m, rad], velocity / max|v|, acceleration / max|a|), measured
(GA3 after its run-in) and held two-sided (tests.support.bounds;
round-off up to 3e-12 held below 3e-11)."""
ROUND_OFF = 3e-12


def truth(scenario: Scenario, times: np.ndarray) -> Trajectory:
    if scenario.family.startswith("cam_") and scenario.parameter("profile") != "disc":
        return reference_solver.solve(scenario, times)
    return exact(scenario, times)


def run(scenario: Scenario, setting: Setting | None = None) -> Trajectory:
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    return result.trajectory


def errors(trajectory: Trajectory, reference: Trajectory) -> list[float]:
    """Absolute position error, then velocity and acceleration errors relative to the largest
    value of their level (with a floor for levels that are zero, like a gear's acceleration)."""
    reference = reference.select(trajectory.bodies)
    out = []
    for level in LEVELS:
        mine, exact_ = trajectory.level(level), reference.level(level)
        assert mine is not None and exact_ is not None
        error = float(np.max(np.abs(mine - exact_)))
        out.append(error if level == "position" else error / max(float(np.max(np.abs(exact_))), 1.0))
    return out


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("name", CATALOGUE)
def test_every_scenario_matches_its_truth(name: str, mode: str) -> None:
    scenario = scenarios.build(name)
    setting = ADAPTER.default_setting(scenario) if mode == "GA3" else Setting.of(mode)
    trajectory = run(scenario, setting)
    reference = truth(scenario, trajectory.times)
    held(errors(trajectory, reference), MEASURED[(name, mode)], round_off=ROUND_OFF)
    for extra, values in reference.extras.items():
        np.testing.assert_allclose(trajectory.extras[extra], values, rtol=0, atol=1e-12)


def test_default_is_generalized_alpha_and_in_the_ladder() -> None:
    scenario = scenarios.build("slider_crank")
    default, ladder = ADAPTER.default_setting(scenario), ADAPTER.ladder(scenario)
    assert default.mode == "GA3" and default in ladder
    assert {s.mode for s in ladder} == {"GA3", "GA3-rho0.5", "GA3-modified", "TR2", "STATIC"}
    assert {s.get("rho") for s in ladder} == {None, 0.0, 0.6}
    period = shortest_period(scenario)
    for setting in ladder:  # the rule's ladder of steps per period, never the output grid's
        if setting.mode != "STATIC":
            per_period = period / setting["dt"]
            assert abs(per_period - round(per_period)) < 1e-6 * per_period


def test_unknown_modes_and_options_fail_without_raising() -> None:
    scenario = scenarios.build("slider_crank")
    for setting in (Setting.of("RK4"), Setting.of("GA3", step=1e-4), Setting.of("GA3", cams="penalty")):
        result = ADAPTER.run(scenario, setting)
        assert result.status == "failed" and result.trajectory is None


@pytest.mark.parametrize("name", ["cam_knife_edge", "cam_roller", "cam_flat_face"])
def test_disc_cams_through_user_functions_match_the_distance_connector(name: str) -> None:
    """The same disc contact as a vector connector with constraint and Jacobian user functions,
    phi a coordinate of its own, instead of Exudyn's distance connector (or its prismatic joint
    for the flat face)."""
    scenario = scenarios.build(name)
    trajectory = run(scenario, ADAPTER.default_setting(scenario).replace(cams="user"))
    reference = exact(scenario, trajectory.times)
    position, velocity, acceleration = errors(trajectory, reference)
    assert position < 1e-12 and velocity < 2e-5 and acceleration < 6e-2
    np.testing.assert_allclose(trajectory.extras["contact.phi"], reference.extras["contact.phi"], atol=1e-12)


@pytest.mark.parametrize(
    ("name", "mode"), [("slider_crank", "GA3"), ("four_bar", "TR2"), ("cam_flat_face/spline", "GA3")]
)
def test_masses_do_not_change_a_driven_result(name: str, mode: str) -> None:
    """Zero mass and a hundred times the mass give the scenario's masses' result: only the
    constraints decide. Accelerations carry Newton's round-off over dt^2."""
    scenario = scenarios.build(name)
    setting = Setting.of(mode, dt=scenario.t_end / scenario.steps / 3)
    base = run(scenario, setting)
    for scale in (0.0, 100.0):
        other = run(scenario, setting.replace(mass_scale=scale))
        for level, bound in zip(LEVELS, (1e-14, 1e-10, 1e-6), strict=True):
            mine, theirs = other.level(level), base.level(level)
            assert mine is not None and theirs is not None
            assert np.max(np.abs(mine - theirs)) <= bound * np.max(np.abs(theirs))


def _orders(mode: str, substeps: tuple[int, ...], **options: int) -> np.ndarray:
    """Observed orders of the slider-crank's errors per level when the step halves."""
    scenario = scenarios.build("slider_crank")
    interval = scenario.t_end / scenario.steps
    errs = []
    for k in substeps:
        trajectory = run(scenario, Setting.of(mode, dt=interval / k, **options))
        reference = exact(scenario, trajectory.times)
        errs.append([float(np.max(np.abs(trajectory.level(lv) - reference.level(lv)))) for lv in LEVELS])  # type: ignore[operator]
    e = np.array(errs)
    return np.log2(e[:-1] / e[1:])


def test_generalized_alpha_converges_at_second_order_after_its_run_in() -> None:
    orders = _orders("GA3", (2, 4, 8))
    np.testing.assert_allclose(orders[:, 1:], 2.0, atol=0.1)  # velocities and accelerations


def test_without_its_run_in_generalized_alpha_s_accelerations_are_first_order() -> None:
    """The start-up transient (Arnold and Brüls): O(dt) in the accelerations from an exact start."""
    orders = _orders("GA3", (2, 4, 8), run_in=0)
    np.testing.assert_allclose(orders[:, 1], 2.0, atol=0.1)
    np.testing.assert_allclose(orders[:, 2], 1.0, atol=0.15)


def test_trapezoidal_index_two_converges_at_second_order_with_position_drift() -> None:
    orders = _orders("TR2", (1, 2, 4))
    np.testing.assert_allclose(orders, 2.0, atol=0.1)  # positions drift, O(dt^2), as do the rates


def test_a_path_beyond_the_dead_centre_fails_with_exudyns_message_and_time() -> None:
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.3})
    dead_centre = math.asin(1 / 1.3) / float(scenario.parameter("omega"))
    interval = scenario.t_end / scenario.steps
    for mode in ("GA3", "TR2", "STATIC"):
        result = ADAPTER.run(scenario, Setting.of(mode))
        assert result.status == "failed", mode
        assert result.trajectory is None
        assert result.message.startswith("Exudyn Solve") and "Newton" in result.message
        assert result.failure_time is not None
        assert dead_centre - 2 * interval < result.failure_time < dead_centre + 2 * interval


def test_a_mechanism_that_cannot_assemble_fails_at_the_start() -> None:
    scenario = scenarios.build("four_bar", overrides={"coupler_length": 0.2, "rocker_length": 0.05})
    result = ADAPTER.run(scenario)
    assert result.status == "failed"
    assert "SolveStatic" in result.message or "did not assemble" in result.message
    assert result.failure_time is not None and result.failure_time < 1e-9


@dataclasses.dataclass(frozen=True)
class Weld:
    name: str
    p_i: Point
    p_j: Point


def test_what_exudyn_cannot_represent_is_unsupported_with_its_reason() -> None:
    base = scenarios.build("four_bar")
    undriven = dataclasses.replace(base, drivers=())
    reason = ADAPTER.supports(undriven)
    assert reason is not None and "not kinematically driven" in reason
    assert ADAPTER.run(undriven).status == "unsupported"

    weld: Any = Weld("O4", Point("rocker"), Point("coupler"))  # a joint kind no engine knows
    welded = dataclasses.replace(base, joints=(*base.joints[:-1], weld))
    result = ADAPTER.run(welded)
    assert result.status == "unsupported" and "Weld" in result.message

    zero_link = RevoluteRevolute("link", Point("crank"), Point("rocker"), 0.0)
    pointless = dataclasses.replace(base, joints=(*base.joints[:-1], zero_link))
    result = ADAPTER.run(pointless)
    assert result.status == "unsupported" and "positive length" in result.message


def test_runs_write_no_file_and_print_nothing(
    tmp_path: object, capfd: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(str(tmp_path))
    for name, mode in (("slider_crank", "GA3"), ("cam_roller/spline", "TR2"), ("cam_flat_face", "STATIC")):
        scenario = dataclasses.replace(scenarios.build(name), steps=20)
        assert ADAPTER.run(scenario, Setting.of(mode)).status == "ok"
    failing = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.3})
    assert ADAPTER.run(failing).status == "failed"
    assert os.listdir(str(tmp_path)) == []
    out, err = capfd.readouterr()
    assert out == "" and err == ""


def test_rack_and_pinion_is_a_native_linear_connector() -> None:
    """A guided rack keeps its angle, so the mesh row is linear: Exudyn's coordinate-vector
    connector with constant scaling, no Python constraint or Jacobian function."""
    model = build_model(scenarios.build("rack_pinion"))
    objects = [model.mbs.GetObject(i) for i in range(model.mbs.systemData.NumberOfObjects())]
    vectors = [o for o in objects if o["objectType"] == "ConnectorCoordinateVector"]
    assert vectors and all(str(o["constraintUserFunction"]) == "0" for o in vectors)


def test_the_flat_face_on_a_disc_is_a_native_prismatic_joint_free_to_turn() -> None:
    """The disc's centre slides on the face line moved R towards the disc: Exudyn's 2D prismatic
    joint without its rotation row, no user function and no phi coordinate; exact to round-off
    (1.8e-15 measured, phi 3.6e-15) at the default step."""
    scenario = scenarios.build("cam_flat_face")
    model = build_model(scenario)
    objects = [model.mbs.GetObject(i) for i in range(model.mbs.systemData.NumberOfObjects())]
    free = [o for o in objects if o["objectType"] == "JointPrismatic2D" and not o["constrainRotation"]]
    assert len(free) == 1 and not model.phi_index
    assert not [o for o in objects if o["objectType"] == "ConnectorCoordinateVector"]
    trajectory = run(scenario, ADAPTER.default_setting(scenario))
    reference = exact(scenario, trajectory.times)
    assert errors(trajectory, reference)[0] < 1e-13
    np.testing.assert_allclose(trajectory.extras["contact.phi"], reference.extras["contact.phi"], atol=1e-13)
