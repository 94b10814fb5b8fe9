"""Exudyn adapter on mechanisms outside the catalogue, built from the vocabulary, against the
reference solver: a gear law of three moving bodies (a coordinate-vector connector with linear
scaling), an inclined prismatic guide, a fixed body, point-path and relative-displacement drivers,
a relative rotation driver and a massless link. They show that the adapter walks the description
generically rather than recognising the families.

Measured with Exudyn 1.13.6 (static mode): positions 1e-15, velocities 1e-14, accelerations 1e-12
relative to their largest value; generalized-alpha velocities O(dt^2), 1e-6 relative here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import reference_solver
from adapters.base import Setting
from adapters.exudyn import ExudynAdapter
from scenarios import (
    GROUND,
    AbsoluteDriver,
    Body,
    Constant,
    ConstantSpeed,
    Ground,
    Harmonic,
    Point,
    PointPathDriver,
    Prismatic,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
    Revolute,
    RevoluteRevolute,
    Scenario,
)
from tests.support.mechanisms import differential_train

ADAPTER = ExudynAdapter()


def _scenario(name: str, bodies: tuple[Body, ...], joints: tuple, drivers: tuple, t_end: float) -> Scenario:  # type: ignore[type-arg]
    return Scenario(name, "default", bodies, joints, drivers, t_end, 100, 0.1)


def differential() -> Scenario:
    """A planetary train whose sun and arm both turn: the gear law ties three moving angles."""
    bodies, joints = differential_train(0.06, 0.03)
    drivers = (
        AbsoluteDriver("sun_drive", "sun", "theta", ConstantSpeed(0.0, 4.0)),
        RelativeRotationDriver("arm_drive", "arm", "sun", ConstantSpeed(0.0, 3.0)),
    )
    return _scenario("differential", bodies, joints, drivers, 1.0)


def inclined_slider_crank() -> Scenario:
    """A slider-crank whose guide is inclined by 0.4 rad: the prismatic joint's axis lies in the
    slider's frame, which is itself turned by 0.4 from the ground's."""
    l2, l3, tilt = 0.1, 0.3, 0.4
    bodies = (
        Body("crank", (0.04, 0.02, 0.5), mass=0.1, inertia=1e-4),
        Body("rod", (0.2, 0.1, 0.3), mass=0.3, inertia=2e-3),
        Body("slider", (0.33, 0.14, tilt), mass=0.5, inertia=1e-4),
    )
    joints = (
        Revolute("O", Point(GROUND), Point("crank", (-l2 / 2, 0.0))),
        Revolute("A", Point("crank", (l2 / 2, 0.0)), Point("rod", (-l3 / 2, 0.0))),
        Revolute("B", Point("rod", (l3 / 2, 0.0)), Point("slider")),
        Prismatic("guide", Point("slider"), Point(GROUND, (0.0, 0.0)), axis=(1.0, 0.0), angle=tilt),
    )
    drivers = (AbsoluteDriver("drive", "crank", "theta", ConstantSpeed(0.5, 20.0)),)
    return _scenario("inclined", bodies, joints, drivers, 2 * math.pi / 20.0)


def kitchen_sink() -> Scenario:
    """A fixed base carrying a driven crank; a block whose point follows a path and whose angle
    follows the crank's; a rocker held to the block by a massless link; a shadow body displaced
    from the block by a prescribed vector."""
    bodies = (
        Body("base", (0.1, 0.2, 0.3), mass=1.0, inertia=1e-3),
        Body("crank", (0.12, 0.22, 0.0), mass=0.1, inertia=1e-4),
        Body("block", (0.3, 0.0, 0.2), mass=0.2, inertia=1e-4),
        Body("rocker", (0.45, 0.05, 1.4), mass=0.1, inertia=1e-4),
        Body("shadow", (0.35, 0.05, 0.1), mass=0.1, inertia=1e-4),
    )
    joints = (
        Ground("fix", "base", (0.1, 0.2, 0.3)),
        Revolute("crank_pin", Point("base", (0.02, 0.0)), Point("crank", (-0.03, 0.0))),
        Revolute("rocker_pin", Point(GROUND, (0.45, -0.05)), Point("rocker", (0.0, -0.1))),
        RevoluteRevolute("link", Point("rocker", (0.0, 0.1)), Point("block", (0.02, 0.01)), 0.16),
    )
    drivers = (
        AbsoluteDriver("crank_drive", "crank", "theta", ConstantSpeed(0.0, 5.0)),
        PointPathDriver(
            "path", Point("block", (0.01, 0.0)), Harmonic(0.3, 0.05, 5.0), Harmonic(0.0, 0.04, 5.0, -1.0)
        ),
        RelativeRotationDriver("block_turn", "block", "crank", Constant(0.2)),
        RelativeDisplacementDriver(
            "offset", Point("shadow"), Point("block"), Harmonic(0.05, 0.01, 10.0), Constant(0.05)
        ),
        AbsoluteDriver("shadow_turn", "shadow", "theta", Harmonic(0.1, 0.2, 3.0)),
    )
    return _scenario("kitchen_sink", bodies, joints, drivers, 1.0)


CASES = {"differential": differential, "inclined": inclined_slider_crank, "kitchen_sink": kitchen_sink}


def relative_errors(scenario: Scenario, setting: Setting) -> list[float]:
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok", result.message
    trajectory = result.trajectory
    assert trajectory is not None
    truth = reference_solver.solve(scenario, trajectory.times).select(trajectory.bodies)
    out = []
    for level in ("position", "velocity", "acceleration"):
        mine, exact = trajectory.level(level), truth.level(level)
        assert mine is not None and exact is not None
        out.append(float(np.max(np.abs(mine - exact)) / np.max(np.abs(exact))))
    return out


@pytest.mark.parametrize("case", CASES)
def test_static_mode_matches_the_reference_solver(case: str) -> None:
    position, velocity, acceleration = relative_errors(CASES[case](), Setting.of("STATIC"))
    assert position < 1e-13
    assert velocity < 1e-12
    assert acceleration < 1e-10


@pytest.mark.parametrize("case", CASES)
def test_generalized_alpha_matches_the_reference_solver(case: str) -> None:
    scenario = CASES[case]()
    position, velocity, acceleration = relative_errors(scenario, ADAPTER.default_setting(scenario))
    # exact to Newton's tolerance at the steps; the outputs between two steps are their cubic
    # Hermite interpolant (adapters.lattice)
    assert position < 1e-10
    assert velocity < 2e-5
    assert acceleration < 5e-2


def test_inclined_guide_keeps_the_slider_turned_and_on_its_line() -> None:
    scenario = inclined_slider_crank()
    result = ADAPTER.run(scenario, Setting.of("STATIC"))
    assert result.trajectory is not None
    slider = result.trajectory.position[:, result.trajectory.bodies.index("slider"), :]  # type: ignore[index]
    np.testing.assert_allclose(slider[:, 2], 0.4, atol=1e-14)
    across = -math.sin(0.4) * slider[:, 0] + math.cos(0.4) * slider[:, 1]
    np.testing.assert_allclose(across, 0.0, atol=1e-14)
    assert np.ptp(slider[:, 0]) > 0.15  # and it does slide
