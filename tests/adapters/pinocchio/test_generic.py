"""The Pinocchio adapter builds from the engine-neutral description, not from the family name:
hand-made variants (a massless coupler, a fixed frame body, a turned slider) against the reference
solver or the closed forms; what it refuses; failures with their time; the command line."""

from __future__ import annotations

import dataclasses
import io
import math

import numpy as np
import pandas as pd
import pytest

import scenarios
from adapters.pinocchio import PinocchioAdapter
from reference_solver import solve
from reports.cli.main import main
from scenarios import (
    GROUND,
    AbsoluteDriver,
    Body,
    ConstantSpeed,
    Ground,
    Point,
    Prismatic,
    RevoluteRevolute,
    Scenario,
)
from scenarios.closed_form import exact

LEVELS = ("position", "velocity", "acceleration")
BOUNDS = (1e-12, 1e-11, 1e-9)
"""Measured: the massless coupler 2e-14, 4e-13, 1.2e-10 against the closed form; the four-bar on a
frame body 2e-14, 7e-13, 1.5e-10 against the reference solver (whose own error is of that order)."""


def assert_close(scenario: Scenario, truth_of) -> None:  # type: ignore[no-untyped-def]
    result = PinocchioAdapter().run(scenario)
    assert result.status == "ok", result.message
    trajectory = result.trajectory
    assert trajectory is not None
    truth = truth_of(scenario, trajectory.times).select(trajectory.bodies)
    found = [float(np.max(np.abs(trajectory.level(lv) - truth.level(lv)))) for lv in LEVELS]
    assert all(e < b for e, b in zip(found, BOUNDS, strict=True)), found


def massless_coupler() -> Scenario:
    """The default four-bar with its coupler replaced by a distance constraint."""
    base = scenarios.build("four_bar", overrides={"steps": 60})
    a, b, c = 0.05, 0.1, 0.125
    joints = (
        base.joints[0],
        base.joints[3],
        RevoluteRevolute("AB", Point("crank", (a / 2, 0.0)), Point("rocker", (c / 2, 0.0)), b),
    )
    bodies = (base.body("crank"), base.body("rocker"))
    return dataclasses.replace(base, bodies=bodies, joints=joints, variant="massless")


def test_distance_constraint_closes_the_loop() -> None:
    scenario = massless_coupler()
    assert_close(scenario, lambda s, t: exact(scenarios.build("four_bar"), t))


def on_frame_body() -> Scenario:
    """The four-bar with its pivots on a body fixed at a turned, shifted pose by a Ground joint."""
    base = scenarios.build("four_bar", overrides={"steps": 60})
    pose = (0.02, -0.01, 0.3)

    def moved(guess: tuple[float, float, float]) -> tuple[float, float, float]:
        c, s = math.cos(pose[2]), math.sin(pose[2])
        x, y, th = guess
        return (pose[0] + c * x - s * y, pose[1] + s * x + c * y, th + pose[2])

    bodies = tuple(dataclasses.replace(b, guess=moved(b.guess)) for b in base.bodies)
    pivots = tuple(
        dataclasses.replace(j, p_i=Point("frame", j.p_i.local)) if j.p_i.body == GROUND else j
        for j in base.joints
    )
    drive = AbsoluteDriver("crank_drive", "crank", "theta", ConstantSpeed(0.3 + pose[2], 50.0))
    return dataclasses.replace(
        base,
        bodies=(Body("frame", pose), *bodies),
        joints=(Ground("fix", "frame", pose), *pivots),
        drivers=(drive,),
        variant="on_frame",
    )


def turned_slider() -> Scenario:
    """The slider-crank with the guide written ground-first and the slider's frame turned 90 deg."""
    base = scenarios.build("slider_crank", overrides={"steps": 60, "offset": 0.03})
    slider = dataclasses.replace(base.body("slider"), guess=(*base.body("slider").guess[:2], math.pi / 2))
    guide = Prismatic(
        "slide", Point(GROUND, (0.0, 0.03)), Point("slider"), axis=(1.0, 0.0), angle=-math.pi / 2
    )
    return dataclasses.replace(
        base,
        bodies=(*base.bodies[:2], slider),
        joints=(*base.joints[:3], guide),
        variant="turned",
    )


@pytest.mark.parametrize("build", [on_frame_body, turned_slider])
def test_hand_made_variants_match_the_reference_solver(build) -> None:  # type: ignore[no-untyped-def]
    assert_close(build(), solve)


def test_turned_slider_keeps_its_angle() -> None:
    result = PinocchioAdapter().run(turned_slider())
    assert result.trajectory is not None
    theta = result.trajectory.position[:, 2, 2]
    np.testing.assert_allclose(theta, math.pi / 2, atol=1e-15)


def test_body_outside_the_tree_is_unsupported() -> None:
    base = scenarios.build("four_bar")
    scenario = dataclasses.replace(base, bodies=(*base.bodies, Body("ghost", (0.0, 0.0, 0.0))))
    reason = PinocchioAdapter().supports(scenario)
    assert reason is not None and "ghost" in reason
    assert PinocchioAdapter().run(scenario).status == "unsupported"


def test_undriven_mechanism_is_unsupported_with_the_counts() -> None:
    scenario = dataclasses.replace(scenarios.build("four_bar"), drivers=())
    reason = PinocchioAdapter().supports(scenario)
    assert reason is not None and "(2)" in reason and "(3)" in reason


def test_distance_constraint_runs_in_dynamics_on_rows() -> None:
    """A massless link is no Pinocchio constraint model, but forwardDynamics takes its row: the
    dynamic mode agrees with the kinematic one to RK4's truncation (1000 steps per period)."""
    adapter = PinocchioAdapter()
    scenario = massless_coupler()
    dynamic = adapter.run(scenario, adapter.dynamic_setting(scenario))
    kinematic = adapter.run(scenario, adapter.default_setting(scenario))
    assert dynamic.status == kinematic.status == "ok", dynamic.message
    assert dynamic.trajectory is not None and kinematic.trajectory is not None
    gap = np.abs(dynamic.trajectory.position - kinematic.trajectory.position).max()
    assert gap < 1e-7 * scenario.characteristic_length  # measured 1.3e-8


@pytest.mark.parametrize("mode", ["kinematic", "dynamic"])
def test_dead_centre_is_singular_at_its_time(mode: str) -> None:
    """A full stroke reaches the outer dead centre at t = pi / (2 omega), a grid point here."""
    adapter = PinocchioAdapter()
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.0, "steps": 100})
    setting = adapter.default_setting(scenario) if mode == "kinematic" else adapter.dynamic_setting(scenario)
    result = adapter.run(scenario, setting)
    assert result.status == "singular", result.message
    assert result.failure_time == pytest.approx(math.pi / 100, abs=1e-12)


def test_crossing_a_singular_configuration_between_grid_points_is_caught() -> None:
    """Crank and rod of equal length: singular at th2 = pi / 2, between two grid points here."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.5})
    result = PinocchioAdapter().run(scenario)
    assert result.status == "singular" and result.failure_time is not None
    crossing = (math.pi / 2 - 0.5) / 50
    assert crossing < result.failure_time <= crossing + scenario.t_end / scenario.steps


def test_impossible_assembly_fails_at_time_zero() -> None:
    result = PinocchioAdapter().run(scenarios.build("four_bar", overrides={"crank_length": 0.5}))
    assert result.status == "failed" and result.failure_time == 0.0
    assert "cannot assemble" in result.message


def test_command_line_solves_in_the_dynamic_mode(capsys) -> None:  # type: ignore[no-untyped-def]
    argv = ["solve", "four_bar", "--engine", "pinocchio", "--mode", "dynamic", "--steps", "20"]
    assert main([*argv, "--setting", "dt=1e-4"]) == 0
    frame = pd.read_csv(io.StringIO(capsys.readouterr().out))
    assert len(frame) == 21
    closed = exact(scenarios.build("four_bar"), frame["t"].to_numpy()).to_frame()
    columns = [c for c in closed.columns if c != "t"]
    assert list(frame.columns)[: 1 + len(columns)] == ["t", *columns]
    forces = list(frame.columns)[1 + len(columns) :]  # the drive's torque and the joints' reactions
    assert "crank_drive.force" in forces and all(c.endswith((".fx", ".fy", ".force")) for c in forces)
    assert {"O2.fx", "O2.fy"} <= set(forces)
    np.testing.assert_allclose(frame[columns].to_numpy(), closed[columns].to_numpy(), atol=1e-4, rtol=0)
    positions = [c for c in columns if c.rsplit(".", 1)[1] in ("x", "y", "theta")]
    assert np.max(np.abs(frame[positions].to_numpy() - closed[positions].to_numpy())) < 1e-9


def test_grid_point_on_a_bifurcation_is_singular() -> None:
    """Crank and rod of equal length: at th2 = pi / 2 (a grid point here) the regular branch meets
    the folded one (slider held at the crank pivot); the Jacobian there is exactly singular."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.0, "steps": 8})
    result = PinocchioAdapter().run(scenario)
    assert result.status == "singular"
    assert result.failure_time == pytest.approx(math.pi / 100, abs=1e-12)


def test_overshooting_stroke_stops_where_configurations_end() -> None:
    """With 1.2 times the stroke no configuration exists beyond t* = asin(1 / 1.2) / omega; the
    halving locates it (measured 1.5e-6 after t*)."""
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.2})
    result = PinocchioAdapter().run(scenario)
    assert result.status in ("singular", "failed") and result.failure_time is not None
    assert result.failure_time == pytest.approx(math.asin(1 / 1.2) / 50, abs=1e-5)


def test_coarse_output_grid_stays_on_the_branch() -> None:
    """Four output steps per revolution: intervals are halved until Newton follows the branch."""
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"steps": 4})
    assert_close(scenario, exact)
