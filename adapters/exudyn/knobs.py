"""Exudyn's accuracy knobs (adapters.knobs): what each of its options and solver settings does to
the error and how the ladder (adapters.exudyn.settings) treats it."""

from __future__ import annotations

from adapters.exudyn.settings import RHOS, STEPS_PER_PERIOD
from adapters.knobs import FIXED, NOT_APPLICABLE, SWEPT, Knob

KNOBS = (
    Knob(
        "integrator (mode)",
        SWEPT,
        "GA3, GA3-rho0.5, GA3-modified (Exudyn's modified Newton) and TR2 (index 2, positions drift "
        "O(dt^2)) are curves of their own; STATIC per output time on kinematic scenes; RK44 runs on "
        "request (scenes without joints only)",
    ),
    Knob(
        "dt",
        SWEPT,
        f"rungs of steps per shortest period around the rule's {STEPS_PER_PERIOD}, within the step "
        "budget (shortened so that the outputs fall on steps)",
    ),
    Knob(
        "rho",
        SWEPT,
        "generalized-alpha's spectral radius sets its numerical damping and how fast its start-up "
        f"transient dies: 0.9 and 0.5 as modes, {', '.join(f'{r:g}' for r in RHOS)} at the default step",
    ),
    Knob(
        "run_in",
        SWEPT,
        "steps before the first output that let GA3's start-up transient die (kinematic scenes); "
        "run_in=0 at the default step shows the transient as its own row",
    ),
    Knob(
        "tol",
        FIXED,
        "Newton's tolerance 1e-12 (1e-14 static): positions are exact to it and the accelerations' "
        "floor is its round-off over h^2; Exudyn's own 1e-8 in untuned",
    ),
    Knob(
        "adaptive step reduction",
        FIXED,
        "off (a fixed step with the outputs on its steps), except in untuned, which keeps Exudyn's own",
    ),
    Knob(
        "cams",
        NOT_APPLICABLE,
        "the same cam rows built by Exudyn's elements or by user functions: a route, not an accuracy",
    ),
    Knob(
        "cam_model",
        FIXED,
        "the scene's default cam model (equivalent linkage or contact): another model is another mechanism",
    ),
    Knob("mass_scale", NOT_APPLICABLE, "scales the masses for the mass probe: changes the mechanism"),
)
"""Exudyn's knobs, one per option and per solver setting that could change the error."""
