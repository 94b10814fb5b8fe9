"""The crank worked by hand: a link of length 2 a pinned at its end to the ground origin, its angle
driven by theta = m + A cos(w t), with q, q' and q'' in closed form (tests of the plain and the
compiled kinematic loops); and a pair of bodies Newton cannot start on."""

from __future__ import annotations

import numpy as np

from reference_solver.system import ConstraintSystem
from scenarios import (
    GROUND,
    AbsoluteDriver,
    Body,
    ConstantSpeed,
    Harmonic,
    Point,
    Revolute,
    RevoluteRevolute,
)
from scenarios.scenario import Scenario

A_HALF, MEAN, AMPLITUDE, OMEGA = 0.1, 0.4, 0.7, 3.0


def crank_scenario(guess: tuple[float, float, float] = (0.09, 0.05, 0.5)) -> Scenario:
    return Scenario(
        family="hand_crank",
        variant="default",
        bodies=(Body("crank", guess, length=2 * A_HALF),),
        joints=(Revolute("O", Point(GROUND, (0.0, 0.0)), Point("crank", (-A_HALF, 0.0))),),
        drivers=(AbsoluteDriver("drive", "crank", "theta", Harmonic(MEAN, AMPLITUDE, OMEGA)),),
        t_end=1.0,
        steps=20,
        characteristic_length=2 * A_HALF,
    )


def crank_by_hand(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    th = MEAN + AMPLITUDE * np.cos(OMEGA * t)
    thd = -AMPLITUDE * OMEGA * np.sin(OMEGA * t)
    thdd = -AMPLITUDE * OMEGA**2 * np.cos(OMEGA * t)
    c, s, a = np.cos(th), np.sin(th), A_HALF
    q = np.stack([a * c, a * s, th], axis=1)
    qd = np.stack([-a * s * thd, a * c * thd, thd], axis=1)
    qdd = np.stack([-a * (c * thd**2 + s * thdd), a * (c * thdd - s * thd**2), thdd], axis=1)
    return q, qd, qdd


def unassembled_pair() -> tuple[ConstraintSystem, np.ndarray]:
    """Bodies a and b, L = 0.5, guessed at (0, 0, 0) and (1, 0, 0). Joints: a's origin 0.3 from the
    ground origin, b's 0.2 from the ground point (1, 0) (distance rows |d|^2 - l^2, whose gradient
    2 d vanishes where the points coincide, as at the guess); drivers y_a = 0.1, theta_a = 1.08e-11,
    y_b = 0, theta_b = 1.03e-11 at t = 0 (each moving at 1/s, so the time is read). At the guess
    C_q has two zero rows: Newton stops before its first step."""
    move = 1.0
    scenario = Scenario(
        family="unassembled",
        variant="default",
        bodies=(Body("a", (0.0, 0.0, 0.0)), Body("b", (1.0, 0.0, 0.0))),
        joints=(
            RevoluteRevolute("da", Point(GROUND, (0.0, 0.0)), Point("a"), 0.3),
            RevoluteRevolute("db", Point(GROUND, (1.0, 0.0)), Point("b"), 0.2),
        ),
        drivers=(
            AbsoluteDriver("ya", "a", "y", ConstantSpeed(0.1, move)),
            AbsoluteDriver("ta", "a", "theta", ConstantSpeed(1.08e-11, move)),
            AbsoluteDriver("yb", "b", "y", ConstantSpeed(0.0, move)),
            AbsoluteDriver("tb", "b", "theta", ConstantSpeed(1.03e-11, move)),
        ),
        t_end=1.0,
        steps=1,
        characteristic_length=0.5,
    )
    return ConstraintSystem(scenario), np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0])
