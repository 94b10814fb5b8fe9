"""The compiled residual where the catalogue's cam scenes do not reach: two cam contacts on one cam
(the profile points of each, and the body count taken from a layout with two contact parameters),
and a chain of 81 moving bodies whose 242 rows outnumber the instructions' width and whose bodies
outnumber the kernels' scratch width, each against the plain rows at random states; and a scene with
no constraint at all."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import scenarios
from reference_solver.residual import constraint_residual, plain_constraint_residual
from scenarios.bodies import Point
from scenarios.joints import Prismatic


def two_cams() -> scenarios.Scenario:
    """The knife-edge cam with a second follower on a horizontal guide, touching the same disc."""
    base = scenarios.load("cam_knife_edge", {"steps": "10"})
    pivot, guide, contact = base.joints
    follower = next(b for b in base.bodies if b.name == "follower")
    tip, centre = Point("follower2", (0.0, 0.0)), Point("ground", (0.0, 0.0))
    guide2 = Prismatic("guide2", tip, centre, (1.0, 0.0), 0.0)
    contact2 = dataclasses.replace(contact, name="contact2", tip=tip, phi_guess=0.0)
    return dataclasses.replace(
        base,
        variant="two_cams",
        bodies=(*base.bodies, dataclasses.replace(follower, name="follower2")),
        joints=(pivot, guide, contact, guide2, contact2),
    )


def random_states(scenario: scenarios.Scenario, times: np.ndarray, seed: int) -> scenarios.Trajectory:
    """Every body at a random pose of the characteristic length's size, each contact parameter at a
    random angle of up to two turns either way."""
    rng = np.random.default_rng(seed)
    bodies = tuple(b.name for b in scenario.bodies)
    position = rng.normal(scale=scenario.characteristic_length, size=(len(times), len(bodies), 3))
    extras = {f"{c.name}.phi": rng.uniform(-4 * np.pi, 4 * np.pi, len(times)) for c in scenario.cams}
    return scenarios.Trajectory(times, bodies, position=position, extras=extras)


@pytest.mark.parametrize("seed", range(3))
def test_two_cam_contacts_on_the_compiled_rows_as_on_the_plain(seed: int) -> None:
    scenario = two_cams()
    assert len(scenario.cams) == 2
    trajectory = random_states(scenario, np.asarray(scenario.times()), seed)
    plain = plain_constraint_residual(scenario, trajectory)
    assert np.all(plain > 1e-3)  # far off the constraints
    np.testing.assert_allclose(constraint_residual(scenario, trajectory), plain, rtol=1e-13, atol=0)
    one = dataclasses.replace(trajectory, extras={"contact2.phi": trajectory.extras["contact2.phi"]})
    np.testing.assert_allclose(
        constraint_residual(scenario, one), plain_constraint_residual(scenario, one), rtol=1e-13, atol=0
    )


def test_a_chain_of_81_bodies_on_the_compiled_rows_as_on_the_plain() -> None:
    scenario = scenarios.load("n_four_bar/spec")
    assert len(scenario.bodies) == 81
    trajectory = random_states(scenario, np.array([0.0, 0.37, 1.9]), 7)
    plain = plain_constraint_residual(scenario, trajectory)
    np.testing.assert_allclose(constraint_residual(scenario, trajectory), plain, rtol=1e-13, atol=0)


def test_a_scene_with_no_constraint_has_none_to_violate() -> None:
    """Two free links (the compound pendulum without its pins): no constraint, a residual of 0."""
    pendulum = scenarios.load("compound_pendulum")
    free = dataclasses.replace(pendulum, joints=(), drivers=())
    trajectory = random_states(free, np.asarray(free.times())[:4], 3)
    for measure in (constraint_residual, plain_constraint_residual):
        np.testing.assert_array_equal(measure(free, trajectory), np.zeros(4))
