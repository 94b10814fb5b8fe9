"""MuJoCo's accuracy knobs (adapters.knobs): what each of its options and engine settings does to
the error and how the ladder (adapters.mujoco.settings) treats it."""

from __future__ import annotations

from adapters.knobs import FIXED, NOT_APPLICABLE, SWEPT, Knob
from adapters.mujoco.cam_facets import DEFAULT_PIECES
from adapters.mujoco.mjcf import SCALED_ITERATIONS, SCALED_TOLERANCE
from adapters.mujoco.settings import (
    DIRECT_TC_STEPS,
    DYNAMIC_TC_LADDER,
    DYNAMIC_TC_STEPS,
    IMPEDANCE,
    IMPEDANCES,
    INVWEIGHT,
    OWN_TC_LADDER,
    SCALED_RUNGS,
    STEPS_PER_PERIOD,
    TC_LADDER,
    TC_STEPS,
)


def _steps(values: tuple[float, ...]) -> str:
    return ", ".join(f"{v:g}" for v in values)


KNOBS = (
    Knob(
        "integrator (mode)",
        SWEPT,
        "each integrator is its own curve (RK4 and implicitfast on driven mechanisms, also implicit and "
        "Euler in free dynamics); only RK4 is above first order; the kinematic mode (Newton on MuJoCo's "
        "rows) runs on request",
    ),
    Knob(
        "dt",
        SWEPT,
        f"rungs of steps per shortest period around the rule's {STEPS_PER_PERIOD}, within the step budget",
    ),
    Knob(
        "tc",
        SWEPT,
        f"RK4's error on the constraint mode falls as (dt/tc)^4: {_steps(TC_LADDER)} steps with the "
        f"regulariser scaled (default {TC_STEPS:g}; in free dynamics {_steps(DYNAMIC_TC_LADDER)}, default "
        f"{DYNAMIC_TC_STEPS:g}), {_steps(OWN_TC_LADDER)} with MuJoCo's own",
    ),
    Knob(
        "invweight",
        SWEPT,
        f"scales the regulariser R = (1-d)/d Â that holds a long tc back: {INVWEIGHT:g} by default, "
        f"{_steps(tuple(w for w, _ in SCALED_RUNGS))} and 1 (MuJoCo's own) as rungs",
    ),
    Knob(
        "solref",
        SWEPT,
        f"the direct form (-1/tc^2, -2/tc) at the default's tc and {DIRECT_TC_STEPS:g} steps beside the "
        "time-constant form (at the same tc both give the same errors)",
    ),
    Knob(
        "impedance",
        SWEPT,
        f"solimp's d in R = (1-d)/d Â: {IMPEDANCE} (MuJoCo's stiffest) and {_steps(IMPEDANCES)} at the "
        "default step",
    ),
    Knob(
        "solver tolerance and iterations",
        FIXED,
        f"{SCALED_TOLERANCE:g} and {SCALED_ITERATIONS} with the scaled regulariser (the solver stops on "
        "a relative cost improvement); beyond that they change nothing measured; MuJoCo's own in untuned",
    ),
    Knob("noslip", NOT_APPLICABLE, "changes nothing measured: the mechanism's rows have no friction"),
    Knob(
        "mjENBL_DIAGEXACT",
        NOT_APPLICABLE,
        "ignores invweight0, so it cannot scale away the regulariser that holds a long time constant back",
    ),
    Knob(
        "run-in",
        FIXED,
        "50 steps from the assembled start before t = 0, so the soft constraints begin in steady state",
    ),
    Knob(
        "polynomial",
        SWEPT,
        "a steered clock by default; polycoef's RK4 step ladder at 4 steps of tc with MuJoCo's own "
        "regulariser (it lags by P'' tc^2)",
    ),
    Knob(
        "cam_model",
        SWEPT,
        "disc cams run as their equivalent linkage by default; the contact's step ladders are rungs too",
    ),
    Knob(
        "cam_pieces",
        FIXED,
        f"{DEFAULT_PIECES} facets per turn: fewer throw the follower off, more lower the vertices' "
        "accelerations at a proportional cost (docs/settings-rule.md)",
    ),
    Knob(
        "contact_impedance",
        FIXED,
        "0.99 on cams by contact; its effect alone is not swept (the contact's time constant is tc, "
        "which is)",
    ),
    Knob(
        "preload",
        FIXED,
        "sized from the scene (adapters.mujoco.cam_load) to keep the follower on the cam: a force of "
        "the model, not a setting of its accuracy",
    ),
)
"""MuJoCo's knobs, one per option and per engine setting that could change the error."""
