"""A mechanism family as data: its parameters (each with a type, a range and a unit), variants,
builder and closed form. The registry collects the families; a family never imports the registry.

Every value that enters a family, a default, a variant's or a user's `--set`, is checked here against
its declaration before anything is built, so a bad value gets one message naming the limit.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from scenarios.scenario import ParameterValue, Scenario, ScenarioError
from scenarios.trajectory import Trajectory

MAX_LENGTH = 1e6  # m: a kilometre-sized mechanism is in range, a 1e308 m one is a typo
MAX_RATE = 1e6  # rad/s
MAX_ANGLE = 1e3  # rad, for initial angles
MAX_GRID_STEPS = 10_000_000  # 1e7 grid points of a few bodies is about 2 GB of trajectory
MAX_REVOLUTIONS = 1e5


def range_text(low: float, high: float, low_open: bool, unit: str) -> str:
    """`(0, 1e+06] m`: a range as every message and listing writes it."""
    return f"{'(' if low_open else '['}{low:g}, {high:g}]" + (f" {unit}" if unit else "")


def in_range(number: float, low: float, high: float, low_open: bool) -> bool:
    """Whether `number` is finite and lies in the range (NaN and infinities never do)."""
    above_low = number > low if low_open else number >= low
    return math.isfinite(number) and above_low and number <= high


def declared_value(
    value: object,
    *,
    text: bool,
    integer: bool,
    low: float,
    high: float,
    low_open: bool,
    choices: tuple[str, ...] = (),
    nonzero: bool = False,
) -> str | float | int | None:
    """`value` as its declaration's type (a text among `choices` when there are choices, an integer,
    or a float in the range, 0 excluded if `nonzero`), or None if it is not one: the one check behind
    a family's parameters and an engine's options."""
    if text:
        word = str(value)
        return word if not choices or word in choices else None
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return None
    if not in_range(number, low, high, low_open) or (nonzero and number == 0):
        return None
    if integer:
        return int(number) if number == int(number) else None
    return number


@dataclass(frozen=True)
class Parameter:
    """One family parameter: its default (whose type is the parameter's type), unit and range.

    Numbers lie in [low, high] (`low_open` excludes low itself), `nonzero` excludes 0, and a string
    parameter takes one of `choices`.
    """

    default: ParameterValue
    unit: str = ""
    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    nonzero: bool = False
    choices: tuple[str, ...] = ()

    @property
    def kind(self) -> str:
        if isinstance(self.default, str):
            return "text"
        return "integer" if isinstance(self.default, int) else "number"

    def describe(self) -> str:
        """The declared range in words, as `mbxval list` and every message show it."""
        if self.choices:
            return "one of " + ", ".join(self.choices)
        article = "an" if self.kind == "integer" else "a"
        span = f"{article} {self.kind} in {range_text(self.low, self.high, self.low_open, self.unit)}"
        return span + (", not 0" if self.nonzero else "")

    def check(self, family: str, key: str, value: ParameterValue) -> ParameterValue:
        """`value` converted to the parameter's type; ScenarioError naming the limit otherwise."""
        typed = declared_value(
            value,
            text=isinstance(self.default, str),
            integer=self.kind == "integer",
            low=self.low,
            high=self.high,
            low_open=self.low_open,
            choices=self.choices,
            nonzero=self.nonzero,
        )
        if typed is None:
            raise ScenarioError(f"{family}: {key} must be {self.describe()}, got {value!r}")
        return typed


def length(default: float) -> Parameter:
    """A positive length."""
    return Parameter(default, "m", low=0.0, high=MAX_LENGTH, low_open=True)


def offset(default: float) -> Parameter:
    """A signed length (an offset or a position)."""
    return Parameter(default, "m", low=-MAX_LENGTH, high=MAX_LENGTH)


def speed(default: float) -> Parameter:
    """A drive speed: signed, never zero (the grid spans turns at this speed)."""
    return Parameter(default, "rad/s", low=-MAX_RATE, high=MAX_RATE, nonzero=True)


def angle(default: float) -> Parameter:
    """An initial angle."""
    return Parameter(default, "rad", low=-MAX_ANGLE, high=MAX_ANGLE)


def positive(default: float, high: float, unit: str = "") -> Parameter:
    """A positive number up to `high`."""
    return Parameter(default, unit, low=0.0, high=high, low_open=True)


def count(default: int, low: int, high: int, unit: str = "") -> Parameter:
    """A whole number in [low, high]."""
    return Parameter(default, unit, low=low, high=high)


def choice(default: str, *others: str) -> Parameter:
    """One word out of a few."""
    return Parameter(default, choices=(default, *others))


def time_grid(steps: int = 200) -> dict[str, Parameter]:
    """The grid every revolving family takes: `revolutions` turns in `steps` steps."""
    return {
        "revolutions": positive(1.0, MAX_REVOLUTIONS, "turns"),
        "steps": count(steps, 1, MAX_GRID_STEPS),
    }


ClosedForm = Callable[[Scenario, np.ndarray], Trajectory]
"""`closed_form(scenario, times)`: the exact trajectory of a family's own mechanism on `times`."""


Criterion = Callable[[Scenario, Trajectory], dict[str, float]]
"""`criterion(scenario, trajectory)`: a published benchmark's figures of a run of the family."""


class NoClosedForm(ValueError):
    """The scenario has no closed form: it is not a family's own mechanism, or its family has none."""


@dataclass(frozen=True)
class Family:
    """A mechanism family: every parameter declared, named variants, a builder and a closed form.

    `build(params, variant)` receives every parameter, already checked and typed, and returns the
    scenario. `closed_form(scenario, times)` is the family's independent truth for a scenario it
    built (scenarios.closed_form.exact checks that first); it raises NoClosedForm for the parameters
    it does not cover. None where the family has no closed form.
    """

    name: str
    summary: str
    parameters: Mapping[str, Parameter]
    build: Callable[[dict[str, ParameterValue], str], Scenario]
    variants: Mapping[str, Mapping[str, ParameterValue]]
    closed_form: ClosedForm | None = None
    dynamic: bool = False
    """Forward dynamics (gravity, forces) rather than a driven kinematic analysis: left out of the
    kinematic catalogue until the engines are compared on dynamics."""
    criterion: Criterion | None = None
    """The figures a published benchmark of the family judges a run by (`criterion(scenario,
    trajectory)` -> {"benchmark_error", "benchmark_limit", "invariant_error"}); None where none."""
    singular_passages: str = ""
    """Why the family's motion passes configurations where C_q loses rank ('' where it does not):
    a method that needs independent coordinates cannot be relied on through them, so engines
    choose a default that passes them (the native engine: ALI3-P) and `mbxval list` says why."""

    @property
    def defaults(self) -> dict[str, ParameterValue]:
        return {key: p.default for key, p in self.parameters.items()}
