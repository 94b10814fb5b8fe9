"""Drake's accuracy knobs (adapters.knobs): what each of its options and plant settings does to the
error and how the ladder (adapters.drake.settings) treats it."""

from __future__ import annotations

from adapters.drake.settings import GAINS, KD, KP, PER_PERIOD
from adapters.knobs import FIXED, NOT_APPLICABLE, SWEPT, Knob

KNOBS = (
    Knob(
        "discrete solver",
        FIXED,
        "SAP: the only discrete solver that takes ball and coupler constraints",
    ),
    Knob(
        "dt",
        SWEPT,
        f"the plant's step over {min(PER_PERIOD)} to {max(PER_PERIOD)} steps per shortest period, "
        "within the step budget",
    ),
    Knob(
        "kp",
        SWEPT,
        f"the PD drive's stiffness: {KP:g} by default (SAP's near-rigid regularisation, not the gain, "
        f"sets the drive's compliance), {', '.join(f'{kp:g}' for kp, _ in GAINS)} as a rung",
    ),
    Knob("kd", SWEPT, f"the PD drive's damping, swept with kp: {KD:g} by default"),
    Knob(
        "lead",
        SWEPT,
        "the drive's target at t + lead dt, which the implicit PD reaches at the step's end: 1 by "
        "default, 0 (the target at the step's start) in the untuned point",
    ),
    Knob(
        "velocity",
        SWEPT,
        "velocities the central difference of the steps by default, the plant's state in the untuned point",
    ),
    Knob(
        "SAP near-rigid threshold",
        NOT_APPLICABLE,
        "changes none of the errors here: the loops and the drive are stiffer than it either way",
    ),
)
"""Drake's knobs, one per option and per plant setting that could change the error."""
