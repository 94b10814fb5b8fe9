"""A stiff case: a physical pendulum (a uniform rod on a ground pivot, under gravity) whose tip is
tied by a stiff spring-damper to a ground anchor a rod length below it when hanging, unstretched
there. Released at theta0 from the downward vertical, the spring makes the pendulum ring at about
sqrt(3 k / m) rad/s (for the defaults 1.7e3 rad/s): an explicit integrator needs steps well below
1 / that. `stiffness` and `dt` (the output step, which is also the step a fixed-step engine is given)
are the parameters a stress sweep turns."""

from __future__ import annotations

from scenarios.bodies import GROUND, Point
from scenarios.families import compound_pendulum
from scenarios.families.released import released
from scenarios.family import Family, Parameter, angle, length, positive
from scenarios.forces import SpringDamper
from scenarios.scenario import ParameterValue, Scenario, require_finite, require_positive


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    k, c, dt, t_end = float(p["stiffness"]), float(p["damping"]), float(p["dt"]), float(p["t_end"])
    length = float(p["link_length"])
    require_positive("stiff_spring", stiffness=k, dt=dt, t_end=t_end, link_length=length)
    require_finite("stiff_spring", damping=c)
    steps = max(1, round(t_end / dt))
    rod = {"links": 1, "link_length": length, "theta0": p["theta0"], "gravity": p["gravity"]}
    spring = SpringDamper(
        "spring", Point("link_1", (length / 2, 0.0)), Point(GROUND, (0.0, -2.0 * length)), k, c, length
    )
    return released(
        compound_pendulum.FAMILY,
        rod,
        "stiff_spring",
        variant,
        {**p, "steps": steps},
        f"pendulum held by a stiff spring (k = {k:g} N/m, output step {dt:g} s)",
        forces=(spring,),
    )


MAP_STIFFNESSES = (1e2, 1e4, 1e6, 1e8)
MAP_STEPS = (1e-4, 1e-3, 1e-2)


def map_variant(stiffness: float, dt: float) -> str:
    """The name of the variant at one cell of the stiffness-step map, such as `k1e6_dt1e-3`."""
    return f"k{stiffness:.0e}_dt{dt:.0e}".replace("e+0", "e").replace("e-0", "e-")


MAP_VARIANTS = {map_variant(k, dt): {"stiffness": k, "dt": dt} for k in MAP_STIFFNESSES for dt in MAP_STEPS}
"""The dynamics suite's stability map: stiffness against the step a fixed-step engine is given."""

FAMILY = Family(
    name="stiff_spring",
    summary="a pendulum held by a stiff spring; stiffness and step size are parameters",
    parameters={
        "stiffness": positive(1e6, 1e15, "N/m"),
        "damping": Parameter(0.0, "N s/m", low=0.0, high=1e12),
        "dt": positive(1e-4, 1e3, "s"),
        "link_length": length(0.5),
        "theta0": angle(0.05),
        "gravity": Parameter(9.81, "m/s^2", low=-1e6, high=1e6),
        "t_end": positive(0.1, 1e6, "s"),
    },
    build=_build,
    variants={"damped": {"damping": 20.0}, **MAP_VARIANTS},
    dynamic=True,
)
