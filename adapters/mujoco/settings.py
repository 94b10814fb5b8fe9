"""MuJoCo's settings by the one rule (adapters.step_rule): the step is a fixed number of steps per
shortest period of the motion, the equalities' time constant `tc` (seconds) a fixed number of those
steps, for every scenario whatever its size and its output grid.

A closed loop's accuracy floor (adapters.mujoco.weights) is RK4's error on the constraint mode the
time constant creates, which falls as (dt / tc)^4, and the regulariser's violation, which grows as
tc^2. With the regulariser scaled away (INVWEIGHT) the time constant can be long: TC_STEPS steps
bring the loops' accelerations from 1e-4 to 1e-10 at the same cost on driven scenes, and
DYNAMIC_TC_STEPS from 1e-8 to 1e-9 or 1e-10 in free dynamics. A cam by contact keeps
MuJoCo's own regulariser and OWN_TC_STEPS: a hard contact loses its follower or rings at every
facet's vertex.

The ladder (one work-precision curve per integrator): each integrator over rungs of steps per
period; where a loop is closed, RK4's time constant over TC_LADDER steps (and the direct solref
form) with the regulariser scaled, SCALED_RUNGS, OWN_TC_LADDER with MuJoCo's own, the impedance
(solimp) at the default and a tenth of the default step; and MuJoCo as a new user's model has it
(UNTUNED).
A rung whose run takes more than STEP_BUDGET steps over the horizon (weighted by bodies / 8 above
8 bodies) is left out, the coarsest always kept: the suite's time goes to points that show
something new. Euler at coarse steps is such a rung, swept, never a silent default for large
systems.
"""

from __future__ import annotations

from adapters.base import UNTUNED, Setting
from adapters.probes import MASS, STIFFNESS, Probe
from adapters.step_rule import at_step, rule_step
from scenarios.cam_linkage import default_cam_model
from scenarios.registry import singular_passages
from scenarios.scenario import Scenario

STEPS_PER_PERIOD = 2000
"""MuJoCo's constant of the rule (at 1000 the soft closures' positions are twice as far off, the
cam contacts' penetration four times)."""
TC_STEPS = 128.0
"""The equalities' time constant in rule steps on driven scenes, with the regulariser scaled by
INVWEIGHT."""
DYNAMIC_TC_STEPS = 1024.0
"""The time constant in rule steps in free dynamics. With the regulariser scaled the constraint mode
is what is left of a loop's error, and in free dynamics nothing steers the loop but gravity and the
loads: at TC_STEPS RK4's error on the mode (dt / tc)^4 sets the accelerations (four_bar_gravity
1.8e-8, andrews_squeezer 3.0e-8); at 1024 steps 4.3e-10 and 4.4e-9, where past about 2000 steps the
loop's drift, no longer pulled back, raises them again (andrews_squeezer 7.9e-9 at 2048, 2.3e-8 at
1e4). On driven scenes a polynomial drive would lag by P'' tc^2, so they keep TC_STEPS."""
SINGULAR_TC_STEPS = 32.0
"""The time constant in rule steps in free dynamics through singular passages (a family's
`singular_passages`): near a singular position the scaled regulariser is no longer small beside the
loop's own inverse inertia and the loop sags by it, which a shorter time constant pulls back
(n_four_bar's first second: accelerations 3.9e-8 at 32 steps, 6.0e-7 at 128, 1.3e-6 at 1024)."""
INVWEIGHT = 1e-8
"""The factor on the compiled model's invweight0 by default (adapters.mujoco.weights): the
regulariser's sag below RK4's error on the constraint mode at TC_STEPS (at 1e-6 a loop passing
near a singular position, n_four_bar, sags to 3e-5 m)."""
SCALED_RUNGS = ((1e-6, 128.0), (1e-4, 32.0))
"""(factor, time constant in steps) of the ladder's rungs at larger regularisers."""
OWN_TC_STEPS = 4.0
"""The time constant in rule steps with MuJoCo's own regulariser (cams by contact): at 2 steps RK4
under-resolves the mode (slider-crank accelerations 4.0e-3), past 8 the regulariser's violation
grows as tc^2."""
IMPEDANCE = 0.9999
"""solimp of the equalities: MuJoCo's stiffest."""
LADDERS = {
    "RK4": (200, 600, 2000, 6000, 20000),
    "implicitfast": (600, 2000, 6000, 20000),
    "implicit": (600, 2000, 6000, 20000),
    "Euler": (60, 200, 600, 2000, 6000, 20000),
}
"""Steps per shortest period in the ladder, per integrator."""
KINEMATIC_MODES = ("RK4", "implicitfast")
"""The integrators swept on driven mechanisms (implicit equals implicitfast there, Euler lies
beneath implicitfast)."""
TC_LADDER = (16.0, 64.0, 256.0)
"""RK4's time constant in steps with the regulariser scaled, swept at the default step."""
DYNAMIC_TC_LADDER = (128.0, 256.0, 4096.0)
"""The same in free dynamics, around DYNAMIC_TC_STEPS."""
DIRECT_TC_STEPS = 1.0e4
"""The direct solref form's rungs are at the default's time constant and at this many steps (next
to no stiffness and damping, the loop held by its exact acceleration alone). At the same tc the
direct form gives what the time-constant form gives (impedance 0.9999: b and k differ by 1e-4)."""
OWN_TC_LADDER = (2.0, 4.0, 16.0)
"""RK4's time constant in steps with MuJoCo's own regulariser, swept at the default step."""
IMPEDANCES = (0.99,)
"""Softer impedances swept at the default."""
STEP_BUDGET = 1.0e5
"""Steps over the horizon above which a rung is left out."""


def by_contact(scenario: Scenario) -> bool:
    """Whether the scenario's cams are MuJoCo contacts by default (no equivalent linkage)."""
    return bool(scenario.cams) and default_cam_model(scenario) == "contact"


def scaled_tc_steps(scenario: Scenario) -> float:
    """The default time constant in steps with the regulariser scaled: DYNAMIC_TC_STEPS in free
    dynamics, SINGULAR_TC_STEPS where the loops pass singular positions, TC_STEPS on driven scenes."""
    if scenario.analysis != "dynamic":
        return TC_STEPS
    return SINGULAR_TC_STEPS if singular_passages(scenario) else DYNAMIC_TC_STEPS


def rule_default(scenario: Scenario) -> Setting:
    """RK4 at the rule's step, the stiffest impedance, the time constant scaled_tc_steps with the
    regulariser scaled by INVWEIGHT; OWN_TC_STEPS with MuJoCo's own on cams by contact."""
    dt = rule_step(scenario, STEPS_PER_PERIOD)
    if by_contact(scenario):
        return own_regulariser(Setting.of("RK4", dt=dt, impedance=IMPEDANCE))
    tc = scaled_tc_steps(scenario) * dt
    return Setting.of("RK4", dt=dt, tc=tc, impedance=IMPEDANCE, invweight=INVWEIGHT)


def own_regulariser(setting: Setting, tc_steps: float = OWN_TC_STEPS) -> Setting:
    """`setting` with MuJoCo's own regulariser and `tc_steps` steps of time constant."""
    return setting.replace(invweight=1.0, tc=tc_steps * float(setting["dt"]))


def untuned(scenario: Scenario) -> Setting:
    """MuJoCo as a new user's model has it, at the rule's step."""
    return Setting.of(UNTUNED, dt=rule_step(scenario, STEPS_PER_PERIOD))


def rule_ladder(scenario: Scenario, modes: tuple[str, ...], closes_loops: bool) -> list[Setting]:
    """Each of `modes` over its ladder within the budget (the default's time constant in steps),
    then, where a loop is closed or a cam is a contact, the time constants, the direct form, other
    regularisers, MuJoCo's own and the impedance at the default step, and the default at a tenth
    of it; MuJoCo untuned last."""
    default = rule_default(scenario)
    weight = max(1.0, len(scenario.bodies) / 8)
    settings = []
    for mode in modes:
        for n in LADDERS[mode]:
            dt = rule_step(scenario, n)
            if n == LADDERS[mode][0] or scenario.t_end / dt * weight <= STEP_BUDGET:
                settings.append(Setting(mode, at_step(default, dt).options))
    if closes_loops or by_contact(scenario):
        dt = float(default["dt"])
        if default["invweight"] < 1.0:
            tcs = DYNAMIC_TC_LADDER if scenario.analysis == "dynamic" else TC_LADDER
            settings += [default.replace(tc=k * dt) for k in tcs]
            direct = (float(default["tc"]) / dt, DIRECT_TC_STEPS)
            settings += [default.replace(tc=k * dt, solref=DIRECT_FORM) for k in direct]
            settings += [default.replace(invweight=w, tc=k * dt) for w, k in SCALED_RUNGS]
        settings += [own_regulariser(default, k) for k in OWN_TC_LADDER]
        settings += [default.replace(impedance=imp) for imp in IMPEDANCES]
        finer = at_step(default, dt / 10)
        if scenario.t_end / float(finer["dt"]) * weight <= STEP_BUDGET:
            settings.append(finer)
    settings.append(untuned(scenario))
    return list(dict.fromkeys(settings))


def time_constant(setting: Setting, dt: float) -> float:
    """The equalities' time constant in seconds: `tc`, else OWN_TC_STEPS steps (a setting without
    `invweight` has MuJoCo's own regulariser)."""
    if setting.get("tc") is not None:
        return float(setting["tc"])
    return OWN_TC_STEPS * dt


TIME_FORM, DIRECT_FORM = "timeconst", "direct"
SOLREF_FORMS = (TIME_FORM, DIRECT_FORM)
"""The equalities' solref: MuJoCo's time-constant form (tc, damping ratio 1), or the direct form
(-stiffness, -damping) with the stiffness and damping the same tc sets (1 / tc^2, 2 / tc)."""


def equality_solref(setting: Setting, dt: float) -> tuple[float, float]:
    """The equalities' solref for `setting` at the step `dt`."""
    tc = time_constant(setting, dt)
    if setting.get("solref", TIME_FORM) == DIRECT_FORM:
        return (-1.0 / tc**2, -2.0 / tc)
    return (tc, 1.0)


STRESS_STEPS = (2e-3, 1e-3, 3e-4, 1e-4, 3e-5)
"""The steps (s) of the stiffness probe, after the scenario's own output step."""
STRESS_TC_STEPS = (2.0, 10.0, 50.0)
"""The stiffness probe's time constants, in steps."""
STRESS_IMPEDANCES = (0.9, 0.99, 0.9999)
"""The stiffness probe's impedances (solimp)."""


def probe_settings(probe: Probe, scenario: Scenario, default: Setting) -> list[Setting] | None:
    """MuJoCo's settings for a stress case (adapters.probes), its `default` first. Stiffness: the
    soft equalities' time constant (in steps) and impedance against the step, RK4 and implicitfast.
    Mass: the default and a ten times finer step, the result depending on the masses."""
    if probe == STIFFNESS:
        interval = scenario.t_end / scenario.steps
        grid = [
            Setting(mode, default.options).replace(dt=dt, tc=tc * dt, impedance=impedance)
            for mode in KINEMATIC_MODES
            for dt in (interval, *STRESS_STEPS)
            for tc in STRESS_TC_STEPS
            for impedance in STRESS_IMPEDANCES
        ]
        return [default, *grid]
    if probe == MASS:
        return [default, at_step(default, float(default["dt"]) / 10)]
    return None
