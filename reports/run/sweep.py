"""Parameter sweeps: `--sweep NAME=SPEC` axes and the grid of swept points they make.

A spec is `log:LOW:HIGH:N` (N values evenly spaced in log10), `lin:LOW:HIGH:N` (evenly spaced), or
an explicit list `A,B,C`. Each value is written with SIGNIFICANT digits and that text is the value
the point is built with, so a point's name (scenarios.scenario.point_name) rebuilds it exactly.
Every value is checked against the parameter's declared type and range (scenarios.family) before
anything runs; integer parameters take the rounded values, without repeats.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from scenarios import family
from scenarios.loading import split_point
from scenarios.scenario import POINT_RESERVED, ScenarioError, point_name

SIGNIFICANT = 6
MAX_POINTS = 10_000
"""More swept points than this in one command is a typo, not a study (each point is a scenario run on
every engine over its settings); it is checked before any point is made."""


class SweepError(ValueError):
    """A --sweep that cannot be read: reported as one line, exit status 2."""


@dataclass(frozen=True)
class Axis:
    """One swept parameter and its values, as text."""

    name: str
    values: tuple[str, ...]


def parse_axis(text: str) -> Axis:
    """The axis of one `NAME=SPEC`."""
    name, sep, spec = text.partition("=")
    if not sep or not name or not spec:
        raise SweepError(
            f"--sweep expects NAME=SPEC (log:LOW:HIGH:N, lin:LOW:HIGH:N or A,B,...), got '{text}'"
        )
    if any(c in POINT_RESERVED for c in name):
        raise SweepError(f"--sweep: a parameter name cannot hold any of {POINT_RESERVED!r}, got '{name}'")
    kind, _, rest = spec.partition(":")
    if kind in ("log", "lin") and rest:
        return Axis(name, _spaced(text, kind, rest))
    values = tuple(v.strip() for v in spec.split(","))
    if any(not v or any(c in POINT_RESERVED for c in v) for v in values):
        raise SweepError(f"--sweep {name}: an empty or malformed value in '{spec}'")
    if len(set(values)) != len(values):
        raise SweepError(f"--sweep {name}: a value is given twice in '{spec}'")
    return Axis(name, values)


def _spaced(text: str, kind: str, rest: str) -> tuple[str, ...]:
    parts = rest.split(":")
    try:
        low, high, count = float(parts[0]), float(parts[1]), int(parts[2])
        if len(parts) != 3:
            raise ValueError
    except (ValueError, IndexError):
        raise SweepError(f"--sweep expects {kind}:LOW:HIGH:N (N a whole number), got '{text}'") from None
    if not (math.isfinite(low) and math.isfinite(high)):
        raise SweepError(f"--sweep: the bounds must be finite numbers, got '{text}'")
    if not 1 <= count <= MAX_POINTS:
        raise SweepError(f"--sweep: N must be in [1, {MAX_POINTS}], got {count} in '{text}'")
    if count == 1 and low != high:
        raise SweepError(f"--sweep: one value between two different bounds is ambiguous: '{text}'")
    if kind == "log":
        if low <= 0 or high <= 0:
            raise SweepError(f"--sweep: log spacing needs positive bounds, got '{text}'")
        numbers = np.logspace(math.log10(low), math.log10(high), count)
        numbers[0], numbers[-1] = low, high  # exactly the bounds given, not 10**log10(bound)
    else:
        numbers = np.linspace(low, high, count)
    values = tuple(dict.fromkeys(format_value(float(v)) for v in numbers))
    if len(values) != count:
        raise SweepError(f"--sweep: '{text}' has values closer than {SIGNIFICANT} significant digits")
    return values


def format_value(number: float) -> str:
    """A swept number as text, to SIGNIFICANT digits (the value the point is built with)."""
    return f"{number:.{SIGNIFICANT}g}"


def typed(base: str, axis: Axis) -> Axis:
    """The axis checked against the family parameter's declaration (ScenarioError naming its range);
    an integer parameter's values rounded, without repeats. Scenario files' values are checked when
    their points are built."""
    name = split_point(base)[0]
    if name.endswith(".toml"):
        return axis
    fam = family(name.split("/", 1)[0])
    parameter = fam.parameters.get(axis.name)
    if parameter is None:
        raise ScenarioError(
            f"{fam.name}: unknown parameter '{axis.name}' in --sweep; known: {', '.join(fam.parameters)}"
        )
    if parameter.kind == "integer":
        rounded = []
        for value in axis.values:
            try:
                rounded.append(str(round(float(value))))
            except ValueError:
                raise ScenarioError(
                    f"{fam.name}: {axis.name} must be {parameter.describe()}, got {value!r}"
                ) from None
        axis = Axis(axis.name, tuple(dict.fromkeys(rounded)))
    for value in axis.values:
        parameter.check(fam.name, axis.name, value)
    return axis


def points(bases: Sequence[str], specs: Sequence[str]) -> list[str]:
    """The names of every swept point: each base scenario over the grid of the `specs`' axes (the
    first axis varies slowest). Bad specs raise SweepError, values out of range ScenarioError."""
    axes = [parse_axis(spec) for spec in specs]
    names = [a.name for a in axes]
    if len(set(names)) != len(names):
        raise SweepError(f"--sweep: a parameter is swept twice: {', '.join(names)}")
    total = len(bases) * math.prod(len(a.values) for a in axes)
    if total > MAX_POINTS:
        raise SweepError(f"--sweep: {total} points, more than the {MAX_POINTS} one run takes")
    out = []
    for base in bases:
        checked = [typed(base, axis) for axis in axes]
        for values in itertools.product(*(a.values for a in checked)):
            out.append(point_name(base, dict(zip(names, values, strict=True))))
    return out
