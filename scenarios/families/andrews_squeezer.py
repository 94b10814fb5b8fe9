"""Andrews' squeezing mechanism: seven bodies, one degree of freedom, a motor torque against a stiff
spring, no gravity; the classic index-3 DAE benchmark, solved over 0.03 s.

Source of every number here: the Test Set for IVP Solvers (Mazzia and Magherini, University of Bari,
problem "andrews", file andrews.f revision 1.2 of 2006-10-02, as redistributed in the R package
deTestSet, src/Ex_andrews.f and R/ex_andrews.R): the parameters, the initial state and the
reference solution at t = 0.03 s (subroutine andsoln, PSIDE at rtol = atol = 1e-14). The problem is
Hairer and Wanner, Solving ODEs II, section VII.7, after Manning and Schiehlen.

The test set writes the mechanism in seven joint angles: beta (body 1 about O), theta (body 2
relative to body 1), gamma (body 3 about B), phi (body 4 relative to body 5), delta (body 5 about A),
omega (body 6 relative to body 7), epsilon (body 7 about A). Here every body has absolute
coordinates with its frame at its centre of mass and its angle the test set's absolute angle
(beta, beta + theta, gamma, phi + delta, delta, omega + epsilon, epsilon); the seven angles come
back as the extra columns andrews.beta ... andrews.epsilon. The test set's equations fix where each
pivot, joint and spring point lies on its body and each pivoted body's centre-of-mass distance from
its pivot; the direction of that offset, which without gravity does not enter the motion, follows the
PyMbs model of the mechanism (bodies 1, 3, 5, 7: (ra, 0), (sb, -sa), (ta, tb), (-ua, -ub)).
"""

from __future__ import annotations

import math

from scenarios.bodies import GROUND, Body, Point
from scenarios.family import MAX_GRID_STEPS, Family, Parameter, count, positive
from scenarios.forces import AppliedTorque, SpringDamper
from scenarios.joints import Revolute
from scenarios.motions import Constant
from scenarios.outputs import AngleOutput
from scenarios.scenario import ParameterValue, Scenario, require_positive

# Test set parameters (andrews.f, R/ex_andrews.R), SI units.
M = (0.04325, 0.00365, 0.02373, 0.00706, 0.07050, 0.00706, 0.05498)
INERTIA = (2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7, 1.169e-5, 5.667e-7, 1.912e-5)
XA, YA, XB, YB, XC, YC = -0.06934, -0.00227, -0.03635, 0.03273, 0.014, 0.072
C0, L0, MOM = 4530.0, 0.07785, 0.033
D, DA, E, EA, RR, RA = 28e-3, 115e-4, 2e-2, 1421e-5, 7e-3, 92e-5
SS, SA, SB, SC, SD = 35e-3, 1874e-5, 1043e-5, 18e-3, 2e-2
TA, TB, U, UA, UB, ZF, ZT, FA = 2308e-5, 916e-5, 4e-2, 1228e-5, 449e-5, 2e-2, 4e-2, 1421e-5

ANGLES = ("beta", "theta", "gamma", "phi", "delta", "omega", "epsilon")
INITIAL = (
    -0.0617138900142764496358948458001,
    0.0,
    0.455279819163070380255912382449,
    0.222668390165885884674473185609,
    0.487364979543842550225598953530,
    -0.222668390165885884674473185609,
    1.23054744454982119249735015568,
)
"""The test set's consistent initial angles (velocities are zero)."""
INITIAL_ACCELERATIONS = (14222.4439199541138705911625887, -10666.8329399655854029433719415, 0, 0, 0, 0, 0)
"""The test set's consistent initial angular accelerations (yini(15:21))."""
REFERENCE_T = 0.03
REFERENCE = (
    0.1581077119629904e2,
    -0.1575637105984298e2,
    0.4082224013073101e-1,
    -0.5347301163226948,
    0.5244099658805304,
    0.5347301163226948,
    0.1048080741042263e1,
)
"""The seven angles at t = 0.03 s, the test set's reference solution (andsoln, y(1..7))."""


def _rot(angle: float, x: float, y: float) -> tuple[float, float]:
    c, s = math.cos(angle), math.sin(angle)
    return c * x - s * y, s * x + c * y


def _body(name: str, k: int, origin: tuple[float, float], angle: float, com: tuple[float, float]) -> Body:
    """Body k + 1 with its centre of mass at `com` (local to the test set's frame at `origin`)."""
    dx, dy = _rot(angle, *com)
    return Body(name, (origin[0] + dx, origin[1] + dy, angle), mass=M[k], inertia=INERTIA[k])


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    stiffness, torque = float(p["spring_stiffness"]), float(p["torque"])
    require_positive("andrews_squeezer", spring_stiffness=stiffness, t_end=float(p["t_end"]))
    beta, theta, gamma, phi, delta, omega, epsilon = INITIAL
    p1 = _rot(beta, RR, 0.0)
    g = (XA + ZT * math.cos(delta), YA + ZT * math.sin(delta))
    h = (XA + U * math.sin(epsilon), YA - U * math.cos(epsilon))
    bodies = (
        _body("k1", 0, (0.0, 0.0), beta, (RA, 0.0)),
        _body("k2", 1, p1, beta + theta, (-DA, 0.0)),
        _body("k3", 2, (XB, YB), gamma, (SB, -SA)),
        _body("k4", 3, g, phi + delta, (0.0, -(E - EA))),
        _body("k5", 4, (XA, YA), delta, (TA, TB)),
        _body("k6", 5, h, omega + epsilon, (ZF - FA, 0.0)),
        _body("k7", 6, (XA, YA), epsilon, (-UA, -UB)),
    )
    f2 = Point("k2", (DA - D, 0.0))
    joints = (
        Revolute("O", Point(GROUND, (0.0, 0.0)), Point("k1", (-RA, 0.0))),
        Revolute("P", Point("k1", (RR - RA, 0.0)), Point("k2", (DA, 0.0))),
        Revolute("B", Point(GROUND, (XB, YB)), Point("k3", (-SB, SA))),
        Revolute("A5", Point(GROUND, (XA, YA)), Point("k5", (-TA, -TB))),
        Revolute("A7", Point(GROUND, (XA, YA)), Point("k7", (UA, UB))),
        Revolute("G", Point("k5", (ZT - TA, -TB)), Point("k4", (0.0, E - EA))),
        Revolute("H", Point("k7", (UA, UB - U)), Point("k6", (-(ZF - FA), 0.0))),
        Revolute("F3", f2, Point("k3", (-SB, SA - SS))),
        Revolute("F4", f2, Point("k4", (0.0, -EA))),
        Revolute("F6", f2, Point("k6", (FA, 0.0))),
    )
    spring = SpringDamper(
        "spring", Point("k3", (SD - SB, SA - SC)), Point(GROUND, (XC, YC)), stiffness, 0.0, L0
    )
    motor = AppliedTorque("motor", "k1", Constant(torque))
    relative = {"theta": ("k2", "k1"), "phi": ("k4", "k5"), "omega": ("k6", "k7")}
    absolute = {"beta": "k1", "gamma": "k3", "delta": "k5", "epsilon": "k7"}
    angles = tuple(
        AngleOutput(f"andrews.{a}", *relative[a])
        if a in relative
        else AngleOutput(f"andrews.{a}", absolute[a])
        for a in ANGLES
    )
    return Scenario(
        family="andrews_squeezer",
        variant=variant,
        bodies=bodies,
        joints=joints,
        drivers=(),
        t_end=float(p["t_end"]),
        steps=int(p["steps"]),
        characteristic_length=D,
        parameters=tuple(p.items()),
        description="Andrews' squeezing mechanism (Test Set for IVP Solvers): motor torque against a spring",
        forces=(spring, motor),
        analysis="dynamic",
        angle_outputs=angles,
    )


FAMILY = Family(
    name="andrews_squeezer",
    summary="Andrews' squeezing mechanism, 7 bodies, the index-3 DAE benchmark (reference at t = 0.03 s)",
    parameters={
        "spring_stiffness": positive(C0, 1e15, "N/m"),
        "torque": Parameter(MOM, "N m", low=-1e6, high=1e6),
        "t_end": positive(REFERENCE_T, 1e3, "s"),
        "steps": count(30, 1, MAX_GRID_STEPS),
    },
    build=_build,
    variants={},
    dynamic=True,
)
