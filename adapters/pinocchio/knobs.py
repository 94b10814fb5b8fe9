"""Pinocchio's accuracy knobs (adapters.knobs): what each of its options and solver settings does
to the error and how the ladder (adapters.pinocchio.settings) treats it."""

from __future__ import annotations

from adapters.knobs import FIXED, SWEPT, Knob
from adapters.pinocchio.settings import GAIN_FACTORS, PER_PERIOD

KNOBS = (
    Knob(
        "mode",
        SWEPT,
        "kinematic (Newton per output time), dynamic (RK4), baumgarte (RK4 with gains) and euler "
        "(semi-implicit Euler with gains) are curves of their own",
    ),
    Knob(
        "tol",
        SWEPT,
        "the kinematic Newton's residual bound: 1e-5, 1e-9 and 1e-15 (the default) on driven scenes",
    ),
    Knob(
        "dt",
        SWEPT,
        "rungs of steps per shortest period per dynamic mode ("
        + "; ".join(f"{mode} {min(steps)} to {max(steps)}" for mode, steps in PER_PERIOD.items())
        + "), within the step budget",
    ),
    Knob(
        "kp",
        SWEPT,
        "Baumgarte's position gain, critically damped at one radian of the shortest period, times "
        + " and ".join(f"{f:g}" for f in GAIN_FACTORS)
        + " at the default step (with kd)",
    ),
    Knob("kd", SWEPT, "Baumgarte's velocity gain, swept with kp (kd = 2 sqrt(kp))"),
    Knob(
        "proximal settings",
        FIXED,
        "constraintDynamics' ProximalSettings (accuracy 1e-12, mu 1e-8, 10 iterations); not swept, the "
        "modes' step and gains are (its effect alone is not measured)",
    ),
    Knob(
        "gears",
        FIXED,
        "mimic joints in the kinematic mode, coupling rows in the dynamic ones: the same gear relation",
    ),
)
"""Pinocchio's knobs, one per option and per solver setting that could change the error."""
