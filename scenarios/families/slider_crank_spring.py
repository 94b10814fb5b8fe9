"""The catalogue's slider-crank driven by a constant motor torque on the crank against a
spring-damper that ties the slider's pin to a ground anchor on its line of motion, beyond the stroke.
At rest the spring has its free length; the damper dissipates what the motor puts in, so the
energy balance has all its terms: motor work, spring energy, damper loss."""

from __future__ import annotations

from scenarios.bodies import GROUND, Point
from scenarios.families import slider_crank
from scenarios.families.released import released
from scenarios.family import MAX_GRID_STEPS, Family, Parameter, angle, count, length, positive
from scenarios.forces import AppliedTorque, SpringDamper
from scenarios.motions import Constant
from scenarios.scenario import ParameterValue, Scenario, require_finite, require_positive


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    l2, l3 = float(p["crank_length"]), float(p["rod_length"])
    k, c, torque = float(p["stiffness"]), float(p["damping"]), float(p["torque"])
    require_positive("slider_crank_spring", stiffness=k, crank_length=l2, rod_length=l3)
    require_finite("slider_crank_spring", damping=c, torque=torque)
    base = {"crank_length": l2, "rod_length": l3, "theta0": p["theta0"]}
    anchor = 2.0 * (l2 + l3)
    spring = SpringDamper(
        "spring", Point("slider"), Point(GROUND, (anchor, 0.0)), k, c, free_length=anchor - l3
    )
    motor = AppliedTorque("motor", "crank", Constant(torque))
    return released(
        slider_crank.FAMILY,
        base,
        "slider_crank_spring",
        variant,
        p,
        "slider-crank driven by a constant torque against a spring-damper on the slider",
        forces=(spring, motor),
    )


FAMILY = Family(
    name="slider_crank_spring",
    summary="slider-crank, constant motor torque against a spring-damper on the slider",
    parameters={
        "crank_length": length(0.2),
        "rod_length": length(0.4),
        "theta0": angle(0.3),
        "torque": Parameter(2.0, "N m", low=-1e9, high=1e9),
        "stiffness": positive(1000.0, 1e15, "N/m"),
        "damping": Parameter(5.0, "N s/m", low=0.0, high=1e12),
        "t_end": positive(1.0, 1e6, "s"),
        "steps": count(200, 1, MAX_GRID_STEPS),
    },
    build=_build,
    variants={"undamped": {"damping": 0.0}},
    dynamic=True,
)
