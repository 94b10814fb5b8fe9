"""Shared builder and closed form of the cam families: a disc cam pinned at the origin and driven at
constant speed, and a follower translating along the y axis through the cam's centre.

The profile is the eccentric disc (radius R, eccentricity e) or, with `profile=spline`, a periodic
cubic spline through `knots` radii of that disc, or with `profile=lobed` the lobed cam
d(phi) = R + e cos(lobes phi) (e is then the lobes' amplitude; an eccentric disc is nearly the
one-lobe case), whose valleys are concave when e lobes^2 > R - e. Closed forms (disc) with cam angle th:
knife edge y = e sin th + sqrt(R^2 - e^2 cos^2 th); roller y = e sin th + sqrt((R + r)^2 - e^2
cos^2 th); flat face y = R + e sin th.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping

import numpy as np

from scenarios.bodies import GROUND, Body, Point
from scenarios.cam_profiles import EccentricDisc, LobedProfile, Profile, SplineProfile
from scenarios.cams import CamContact
from scenarios.drivers import AbsoluteDriver
from scenarios.family import (
    MAX_LENGTH,
    Family,
    NoClosedForm,
    Parameter,
    angle,
    choice,
    count,
    length,
    speed,
    time_grid,
)
from scenarios.joints import Prismatic, Revolute
from scenarios.link_kinematics import assemble, constant_speed, fixed, frame, unit
from scenarios.motions import ConstantSpeed
from scenarios.scenario import ParameterValue, Scenario, ScenarioError, revolving
from scenarios.trajectory import Trajectory

MAX_KNOTS = 10_000
MAX_LOBES = 100

PARAMETERS: dict[str, Parameter] = {
    "radius": length(0.05),
    "eccentricity": Parameter(0.01, "m", low=0.0, high=MAX_LENGTH),
    "omega": speed(10.0),
    "theta0": angle(0.0),
    "profile": choice("disc", "spline", "lobed"),
    "knots": count(72, 4, MAX_KNOTS),
    "lobes": count(3, 1, MAX_LOBES),
    **time_grid(),
}

SPLINE_VARIANTS: dict[str, dict[str, ParameterValue]] = {"spline": {"profile": "spline"}}

FollowerHeight = Callable[[dict[str, ParameterValue], float, float, float], float]
"""(parameters, R, e, th): a guess of the follower's y for a disc of radius R and eccentricity e at
cam angle th."""
ContactFactory = Callable[[dict[str, ParameterValue], Profile, float], CamContact]
"""(parameters, profile, phi): the cam contact, phi a guess of its contact parameter."""


def build_disc_cam(
    family: str,
    p: dict[str, ParameterValue],
    variant: str,
    follower_height: FollowerHeight,
    contact: ContactFactory,
) -> Scenario:
    """Build a disc-cam scenario of the follower `follower_height` guesses and `contact` joins."""
    big_r, e = float(p["radius"]), float(p["eccentricity"])
    omega, theta0 = float(p["omega"]), float(p["theta0"])
    if not 0.0 <= e < big_r:
        raise ScenarioError(f"{family}: eccentricity must be in [0, radius), got {e}")
    disc = EccentricDisc(big_r, e)
    kind = str(p["profile"])
    profile: Profile
    if kind == "disc":
        profile = disc
    elif kind == "spline":
        profile = SplineProfile.sample(disc, int(p["knots"]))
    else:  # lobed, the only other choice the declaration admits
        profile = LobedProfile(big_r, e, int(p["lobes"]))
    # The follower's guess: the disc's closed form, or for a lobed cam that of a centred disc of the
    # profile's radius where the follower's axis meets it.
    height = (
        follower_height(p, profile.radii(math.pi / 2 - theta0)[0], 0.0, theta0)
        if isinstance(profile, LobedProfile)
        else follower_height(p, big_r, e, theta0)
    )
    mass = math.pi * big_r**2
    bodies = (
        Body("cam", (0.0, 0.0, theta0), mass=mass, inertia=mass * big_r**2 / 2),
        Body("follower", (0.0, height, 0.0), mass=0.2, inertia=1e-4),
    )
    joints = (
        Revolute("pivot", Point(GROUND, (0.0, 0.0)), Point("cam")),
        Prismatic("guide", Point("follower"), Point(GROUND, (0.0, 0.0)), axis=(0.0, 1.0)),
        contact(p, profile, math.pi / 2 - theta0),
    )
    driver = AbsoluteDriver("cam_drive", "cam", "theta", ConstantSpeed(theta0, omega))
    follower = family.removeprefix("cam_").replace("_", "-")
    description = f"{kind} cam with a translating {follower} follower"
    return revolving(family, variant, p, bodies, joints, (driver,), big_r, description)


def disc_cam_family(
    name: str,
    summary: str,
    follower_height: FollowerHeight,
    contact: ContactFactory,
    parameters: Mapping[str, Parameter] = PARAMETERS,
    variants: Mapping[str, Mapping[str, ParameterValue]] | None = None,
) -> Family:
    """The disc-cam family `name` of the follower `follower_height` guesses and `contact` joins: the
    builder above, the closed form below, and the spline variant beside `variants`."""
    return Family(
        name=name,
        summary=summary,
        parameters=parameters,
        build=functools.partial(build_disc_cam, name, follower_height=follower_height, contact=contact),
        closed_form=disc_cam_closed_form,
        variants={**SPLINE_VARIANTS, **(variants or {})},
    )


def disc_cam_closed_form(s: Scenario, t: np.ndarray) -> Trajectory:
    """The eccentric disc's exact kinematics (module docstring) for the family's follower, with the
    contact parameter phi as the extra `contact.phi` (positions only); NoClosedForm for the spline
    and lobed profiles."""
    if s.parameter("profile") != "disc":
        raise NoClosedForm("closed forms exist for the eccentric disc profile only")
    big_r, e = float(s.parameter("radius")), float(s.parameter("eccentricity"))
    th, w, al = constant_speed(s, t)
    n = len(t)
    zero = np.zeros(n)
    centre = e * unit(th)  # the disc's centre, global
    if s.family == "cam_flat_face":
        y, dy, ddy = big_r + e * np.sin(th), e * np.cos(th), -e * np.sin(th)
        contact = centre + np.array([0.0, big_r])
    else:
        rr = float(s.parameter("roller_radius")) if s.family == "cam_roller" else 0.0
        g = (big_r + rr) ** 2 - (e * np.cos(th)) ** 2
        y = e * np.sin(th) + np.sqrt(g)
        dy = e * np.cos(th) + e**2 * np.sin(2 * th) / (2 * np.sqrt(g))
        ddy = (
            -e * np.sin(th) + e**2 * np.cos(2 * th) / np.sqrt(g) - (e**2 * np.sin(2 * th)) ** 2 / (4 * g**1.5)
        )
        follower = np.column_stack([zero, y])
        contact = centre + big_r * (follower - centre) / np.linalg.norm(follower - centre, axis=1)[:, None]
    # phi: the polar angle of the contact point in the cam's frame.
    phi = np.unwrap(np.arctan2(contact[:, 1], contact[:, 0]) - th)
    phi += 2 * math.pi * round((math.pi / 2 - th[0] - phi[0]) / (2 * math.pi))
    follower_kin = (
        np.column_stack([zero, y]),
        np.column_stack([zero, dy * w]),
        np.column_stack([zero, ddy * w**2 + dy * al]),
    )
    return assemble(
        t,
        {"cam": frame(fixed(n, 0.0, 0.0), th, w, al), "follower": frame(follower_kin, zero, zero, zero)},
        extras={"contact.phi": phi},
    )
