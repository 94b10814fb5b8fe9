"""A scenario: one fully described mechanism, with its time grid and what it asks to be compared."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

from scenarios.bodies import Body
from scenarios.cams import CamContact
from scenarios.drivers import Driver
from scenarios.forces import Force
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Joint
from scenarios.outputs import AngleOutput

Level = Literal["position", "velocity", "acceleration"]
Analysis = Literal["kinematic", "dynamic"]
LEVELS: tuple[Level, ...] = ("position", "velocity", "acceleration")

Constraint = Joint | GearPair | RackPinion | CamContact | Driver
ParameterValue = float | int | str


class ScenarioError(ValueError):
    """A scenario cannot be built: unknown name or parameter, or a non-physical value."""


@dataclass(frozen=True)
class Scenario:
    """An engine-neutral planar mechanism.

    `joints` hold every time-independent constraint (joints, gears, cam contacts); `drivers` the
    prescribed motions. `outputs` names the bodies compared; `levels` the analysis levels that make
    sense for the scene. Lengths in errors are divided by `characteristic_length`.

    Dynamics: `gravity` (m/s^2, global axes) acts on every body's centre of mass, which is its
    frame origin; `forces` are the applied loads and spring-dampers. `analysis` "dynamic" asks for
    forward dynamics (the drivers leave degrees of freedom the forces move); "kinematic" scenes
    are fully driven, and their loads give the drivers' forces by inverse dynamics.
    `angle_outputs` are extra columns of absolute or joint angles.
    """

    family: str
    variant: str
    bodies: tuple[Body, ...]
    joints: tuple[Joint | GearPair | RackPinion | CamContact, ...]
    drivers: tuple[Driver, ...]
    t_end: float
    steps: int
    characteristic_length: float
    outputs: tuple[str, ...] = ()
    levels: tuple[Level, ...] = LEVELS
    parameters: tuple[tuple[str, ParameterValue], ...] = field(default=())
    description: str = ""
    gravity: tuple[float, float] = (0.0, 0.0)
    forces: tuple[Force, ...] = ()
    analysis: Analysis = "kinematic"
    angle_outputs: tuple[AngleOutput, ...] = ()
    point: tuple[tuple[str, str], ...] = ()
    """The overrides that make this scenario a point of a parameter sweep (`point_name`): its
    name carries them, so that every point is stored under a name of its own."""
    characteristic_rate: float | None = None
    """The rate (rad/s) errors in rates are divided by (to the power of the level); None: derived
    (`characteristic_rate`)."""

    @property
    def name(self) -> str:
        """`family` or `family/variant` for a named variant; `...[k=v,...]` for a swept point."""
        base = self.family if self.variant == "default" else f"{self.family}/{self.variant}"
        return point_name(base, dict(self.point))

    @property
    def body_names(self) -> tuple[str, ...]:
        return tuple(b.name for b in self.bodies)

    @property
    def output_bodies(self) -> tuple[str, ...]:
        return self.outputs or self.body_names

    @property
    def cams(self) -> tuple[CamContact, ...]:
        return tuple(j for j in self.joints if isinstance(j, CamContact))

    def body(self, name: str) -> Body:
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    def parameter(self, name: str) -> ParameterValue:
        return dict(self.parameters)[name]

    def times(self, t_end: float | None = None, steps: int | None = None) -> list[float]:
        """The output grid: `steps` equal steps over [0, t_end], both ends included."""
        t_end = self.t_end if t_end is None else t_end
        steps = self.steps if steps is None else steps
        return [t_end * k / steps for k in range(steps + 1)]


def characteristic_rate(scenario: Scenario) -> float:
    """The rate scale of the scenario's errors: the declared one, else |omega| of a family that has
    that parameter (its drive speed), else 2 pi / t_end (one cycle over the run)."""
    if scenario.characteristic_rate is not None:
        return scenario.characteristic_rate
    try:
        rate = abs(float(scenario.parameter("omega")))
    except (KeyError, TypeError, ValueError):
        rate = math.nan
    if not (math.isfinite(rate) and rate > 0):
        rate = 2.0 * math.pi / scenario.t_end
    return rate


POINT_RESERVED = "[],="
"""Characters a swept parameter's name or value cannot hold: they delimit the point in its name."""


def point_name(base: str, overrides: dict[str, str]) -> str:
    """A swept point's name, `four_bar[crank_length=0.08,omega=50]`: the scenario's name and the
    values that make the point, in the order given, so that every point of a sweep has a stable
    name of its own from which it can be rebuilt (scenarios.loading). Just `base` without overrides."""
    if not overrides:
        return base
    return base + "[" + ",".join(f"{key}={value}" for key, value in overrides.items()) + "]"


def require_positive(family: str, **values: float) -> None:
    """Raise ScenarioError naming the first value that is not a finite positive number."""
    for key, value in values.items():
        if not (math.isfinite(value) and value > 0.0):
            raise ScenarioError(f"{family}: {key} must be a positive number, got {value!r}")


def require_finite(family: str, **values: float) -> None:
    """Raise ScenarioError naming the first value that is not finite."""
    for key, value in values.items():
        if not math.isfinite(value):
            raise ScenarioError(f"{family}: {key} must be a finite number, got {value!r}")


def revolving(
    family: str,
    variant: str,
    p: dict[str, ParameterValue],
    bodies: tuple[Body, ...],
    joints: tuple[Joint | GearPair | RackPinion | CamContact, ...],
    drivers: tuple[Driver, ...],
    characteristic_length: float,
    description: str,
) -> Scenario:
    """The families' common shape: a scenario whose grid spans `revolutions` turns at speed `omega`,
    in `steps` steps, recording every parameter."""
    return Scenario(
        family=family,
        variant=variant,
        bodies=bodies,
        joints=joints,
        drivers=drivers,
        t_end=float(p["revolutions"]) * 2.0 * math.pi / abs(float(p["omega"])),
        steps=int(p["steps"]),
        characteristic_length=characteristic_length,
        parameters=tuple(p.items()),
        description=description,
    )
