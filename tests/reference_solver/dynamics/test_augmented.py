"""The augmented equations [M C_q^T; C_q 0] [q''; lambda] = [Q_e; Q_d] against a hand-solved body and
against the unscaled saddle-point system, and what the multipliers mean: held mechanisms at rest
under gravity, whose joint reactions and driving forces and torques follow from statics by hand
(links of 0.5 m and 1 kg, g = 9.81)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.linalg import LinAlgWarning

import scenarios
from reference_solver import analyse
from reference_solver.dynamics import inverse_dynamics
from reference_solver.dynamics.augmented import accelerations
from scenarios import GROUND, Body, Constant, Point, Scenario
from scenarios.drivers import AbsoluteDriver, PointPathDriver
from scenarios.joints import Prismatic, RevoluteRevolute

G = 9.81
MASS = np.array([2.0, 2.0, 0.5])


def test_a_body_with_prescribed_accelerations_of_its_centre_turns_under_its_torque() -> None:
    """Rows 2 x'' = 0.5 and 3 y'' = -1.5 (not unit rows): x'' = 0.25, y'' = -0.5, theta'' = T / J,
    and the multipliers from m x'' + 2 lambda_1 = f_x, m y'' + 3 lambda_2 = f_y."""
    jac = np.array([[2.0, 0.0, 0.0], [0.0, 3.0, 0.0]])
    qdd, lam = accelerations(jac, MASS, np.array([1.0, -4.0, 0.6]), np.array([0.5, -1.5]))
    np.testing.assert_allclose(qdd, [0.25, -0.5, 1.2], rtol=1e-15)
    np.testing.assert_allclose(lam, [(1.0 - 2.0 * 0.25) / 2, (-4.0 + 2.0 * 0.5) / 3], rtol=1e-15)


def test_rows_in_very_different_units_give_the_accelerations_to_round_off() -> None:
    """Masses from 1e-12 to 1 and rows from 1e-6 to 1e6 (a gram-millimetre body beside a kilogram one),
    the answer chosen first (Q_e = M q'' + C_q^T lambda, Q_d = C_q q''): q'' within 1e-13 on six draws
    (measured 2.8e-14; the same solve without the rows scaled to unit length: 3.2e-12)."""
    mass = np.array([1e-6, 1e-6, 1e-12, 1.0, 1.0, 1e-3])
    units = np.array([1e6, 1e-6, 1.0, 1e3])
    for seed in range(6):
        rng = np.random.default_rng(seed)
        jac = rng.uniform(-1.0, 1.0, (4, 6)) * units[:, None]
        qdd, lam = rng.uniform(-1.0, 1.0, 6), rng.uniform(-1.0, 1.0, 4) / units
        found, multipliers = accelerations(jac, mass, mass * qdd + jac.T @ lam, jac @ qdd)
        np.testing.assert_allclose(found, qdd, rtol=0, atol=1e-13)
        np.testing.assert_allclose(multipliers * units, lam * units, rtol=0, atol=2e-15)  # measured 6.7e-16


def test_a_constraint_row_of_zeros_is_refused_as_singular() -> None:
    """A row that constrains nothing (C_q row 0): the saddle-point matrix is singular, which LU says."""
    jac = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        with pytest.raises(LinAlgWarning, match="Singular matrix"):
            accelerations(jac, MASS, np.zeros(3), np.zeros(2))


def held(name: str, bodies: tuple[Body, ...], joints: tuple, drivers: tuple) -> dict[str, np.ndarray]:  # type: ignore[type-arg]
    scenario = Scenario(name, "default", bodies, joints, drivers, 0.1, 1, 0.5, gravity=(0.0, -G))
    return inverse_dynamics(scenario, analyse(scenario, [0.0, 0.1]))


def test_two_links_held_horizontal_carry_the_weight_through_both_pins() -> None:
    """Link 2 hangs from link 1's end: pin 2 pushes link 1 down by m g, pin 1 up by 2 m g; the
    torques about the centres are m g l/2 on link 2 and (m + 2 m) g l/2 on link 1."""
    chain = scenarios.build("compound_pendulum", overrides={"links": 2, "theta0": math.pi / 2})
    drivers = tuple(AbsoluteDriver(f"hold_{k}", f"link_{k}", "theta", Constant(0.0)) for k in (1, 2))
    extras = held("chain", chain.bodies, chain.joints, drivers)
    assert [b.mass for b in chain.bodies] == [1.0, 1.0]
    np.testing.assert_allclose(extras["hold_2.force"], G * 0.5 / 2, rtol=1e-12)
    np.testing.assert_allclose(extras["hold_1.force"], 3 * G * 0.5 / 2, rtol=1e-12)
    np.testing.assert_allclose(extras["pin_1.fy"], 2 * G, rtol=1e-12)
    np.testing.assert_allclose(extras["pin_2.fy"], -G, rtol=1e-12)
    np.testing.assert_allclose([extras["pin_1.fx"], extras["pin_2.fx"]], 0.0, atol=1e-12)


def test_a_rod_held_at_its_tip_by_a_point_path_driver_names_each_row_s_force() -> None:
    """The tip 0.25 m right of the centre holds the weight (up, m g); the angle's driver then holds
    the tip force's moment about the centre: -m g 0.25."""
    rod = Body("rod", (0.0, 0.0, 0.0), mass=1.0, inertia=0.02)
    tip = PointPathDriver("tip", Point("rod", (0.25, 0.0)), Constant(0.25), Constant(0.0))
    extras = held("rod", (rod,), (), (tip, AbsoluteDriver("level", "rod", "theta", Constant(0.0))))
    np.testing.assert_allclose(extras["tip.y.force"], G, rtol=1e-12)
    np.testing.assert_allclose(extras["tip.x.force"], 0.0, atol=1e-12)
    np.testing.assert_allclose(extras["level.force"], -G * 0.25, rtol=1e-12)


def test_a_slide_and_a_distance_link_carry_the_weight_of_the_body_below_them() -> None:
    """A block on a horizontal slide (held in x) and a bob hanging 0.4 m below a fixed point on a
    massless distance link (held in x and angle): each joint pushes its body up by m g."""
    block = Body("block", (0.1, 0.0, 0.0), mass=2.0, inertia=0.01)
    bob = Body("bob", (0.0, -0.4, 0.0), mass=3.0, inertia=0.01)
    slide = Prismatic("slide", Point(GROUND, (0.0, 0.0)), Point("block", (0.0, 0.0)))
    link = RevoluteRevolute("link", Point(GROUND, (0.0, 0.0)), Point("bob", (0.0, 0.0)), 0.4)
    drivers = (
        AbsoluteDriver("push", "block", "x", Constant(0.1)),
        AbsoluteDriver("bob_x", "bob", "x", Constant(0.0)),
        AbsoluteDriver("bob_theta", "bob", "theta", Constant(0.0)),
    )
    extras = held("two", (block, bob), (slide, link), drivers)
    np.testing.assert_allclose(extras["slide.fy"], 2.0 * G, rtol=1e-12)
    np.testing.assert_allclose(extras["link.fy"], 3.0 * G, rtol=1e-12)
    np.testing.assert_allclose([extras["slide.fx"], extras["link.fx"], extras["push.force"]], 0.0, atol=1e-12)
