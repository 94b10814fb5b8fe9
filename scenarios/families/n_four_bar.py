"""The IFToMM multibody benchmark A02, the N-four-bar mechanism: N parallelogram four-bar loops in a
row (the catalogue's four_bar_chain geometry), 2N + 1 uniform links of 1 m and 1 kg, under gravity
9.81 N/kg in -y, released with the x velocity of point B0 (the crank's tip) at 1 m/s. Source: the
benchmark's specification, lim.ii.udc.es/mbsbenchmark/dist/A02/A02_specification.xml (N = 40 over
20 s; N = 2 over 10 s in its OpenSim reproduction). The specification gives the initial position as
a figure; here the rockers start vertical (theta0 = pi/2), so the chain swings down through the
horizontal position, where all links line up and the degrees of freedom jump from 1 to N + 1
(C_q loses N ranks): the singular configuration every solver must pass on the parallelogram branch.
The default horizon, 4 s, passes it four times; the partitioned method keeps every rocker at the
crank's angle to 1e-14 and the energy to about 1e-9 of the kinetic energy there, and crosses the
benchmark's 10 s too (reference_solver.dynamics.partition_passage). The family declares its
passages (`singular_passages`), so the native engine defaults to ALI3-P, which needs no independent
coordinates; the specification's own criterion is `criterion` (n_four_bar_reference).
"""

from __future__ import annotations

import math
from dataclasses import replace

from scenarios.families import four_bar_chain
from scenarios.families.n_four_bar_reference import criterion
from scenarios.families.released import released
from scenarios.family import MAX_GRID_STEPS, Family, Parameter, angle, count, positive
from scenarios.scenario import ParameterValue, Scenario, require_finite


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    speed, gravity, theta0 = float(p["speed"]), float(p["gravity"]), float(p["theta0"])
    require_finite("n_four_bar", speed=speed, gravity=gravity, theta0=theta0)
    chain = {"loops": p["loops"], "link_length": 1.0, "coupler_length": 1.0, "theta0": theta0}
    scenario = released(
        four_bar_chain.FAMILY,
        chain,
        "n_four_bar",
        variant,
        p,
        f"IFToMM A02: {p['loops']} four-bar loops under gravity, through the singular horizontal position",
        gravity=(0.0, -gravity),
    )
    # Every rocker turns with the crank (tip speed `speed` along x at the start); couplers translate.
    omega = -speed / math.sin(theta0) if math.sin(theta0) != 0.0 else 0.0
    tip = (-omega * math.sin(theta0), omega * math.cos(theta0))
    bodies = tuple(
        replace(b, rate=(tip[0], tip[1], 0.0))
        if b.name.startswith("coupler")
        else replace(b, rate=(tip[0] / 2, tip[1] / 2, omega))
        for b in scenario.bodies
    )
    return replace(scenario, bodies=bodies)


FAMILY = Family(
    name="n_four_bar",
    summary="IFToMM A02: N four-bar loops under gravity passing their singular horizontal position",
    parameters={
        "loops": count(2, 1, 74),
        "speed": Parameter(1.0, "m/s", low=-1e6, high=1e6),
        "theta0": angle(math.pi / 2),
        "gravity": Parameter(9.81, "m/s^2", low=-1e6, high=1e6),
        "t_end": positive(4.0, 1e6, "s"),
        "steps": count(160, 1, MAX_GRID_STEPS),
    },
    build=_build,
    variants={"spec": {"loops": 40, "t_end": 20.0}},
    dynamic=True,
    criterion=criterion,
    singular_passages=(
        "every swing passes the horizontal position, where all links line up and C_q loses N ranks"
    ),
)
