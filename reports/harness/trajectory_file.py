"""A trajectory made by another tool, read from the canonical CSV (scenarios.trajectory) and checked
against the scenario it claims to solve, before anything is scored or stored.

The file has the column `t`, then `<body>.x <body>.y <body>.theta` (position), `.vx .vy .omega`
(velocity), `.ax .ay .alpha` (acceleration) per body, and optionally the extra columns an engine
writes for the scenario, kept but not scored: a cam's contact angle `<cam>.phi`, angle outputs,
`<joint>.fx` and `<driver>.force` (reactions and driving forces, named after the scenario's own
joints, drivers and forces) and `energy.*`. Bodies and levels may be missing: a level is scored when every
scored body has it, and what is left out is said. Refused, with a TrajectoryFileError naming the
file: an unreadable file, an unknown column, a body's level with some of its three columns only, a
non-finite or non-numeric value, and a time column that is not the scenario's grid.
"""

from __future__ import annotations

import io
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from scenarios.files.bounded_read import MAX_TRAJECTORY_CSV_BYTES, FileRefused, read_bounded_text
from scenarios.files.schema import suggestion
from scenarios.scenario import LEVELS, Level, Scenario
from scenarios.trajectory import COLUMNS, Trajectory

GRID_TOLERANCE = 1e-9
"""A time may differ from the scenario's grid by this much times t_end (written-out rounding)."""

MAX_MAGNITUDE = 1e100
"""The largest |value| a trajectory file may hold: far beyond any mechanism in range (lengths and
rates up to 1e6: accelerations up to 1e18), and small enough that every error and its square stay
finite, so that an error is never lost to overflow."""

NUMBER = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?")
"""A CSV number: ASCII digits, an optional point and exponent (not Python's wider float(): no `1_0`,
no `nan`, no `inf`, no other scripts' digits), with spaces around it allowed."""


class TrajectoryFileError(ValueError):
    """A trajectory file that cannot be scored: the message is `FILE: what is wrong`."""


@dataclass(frozen=True)
class ImportedTrajectory:
    """The file's trajectory on the scenario's own grid, and what it leaves out.

    `trajectory` holds the scored bodies (the scenario's outputs the file has) and the levels every
    one of them has; `notes` say in words what was left out and why."""

    source: str
    trajectory: Trajectory
    missing_bodies: tuple[str, ...]
    missing_levels: tuple[Level, ...]
    notes: tuple[str, ...]


ENERGY = "energy"
"""The prefix of the energy columns of a dynamic run (`energy.kinetic`, ...)."""


def extra_columns(scenario: Scenario) -> tuple[str, ...]:
    """The named extra columns a trajectory of `scenario` may carry: cam angles, angle outputs."""
    return tuple(f"{cam.name}.phi" for cam in scenario.cams) + tuple(a.name for a in scenario.angle_outputs)


def is_extra(column: str, scenario: Scenario) -> bool:
    """Whether `column` is an extra an engine writes for `scenario` (see the module docstring)."""
    owners = {c.name for c in (*scenario.joints, *scenario.drivers, *scenario.forces)} | {ENERGY}
    return column in extra_columns(scenario) or ("." in column and column.split(".")[0] in owners)


def _fail(source: str, message: str) -> TrajectoryFileError:
    return TrajectoryFileError(f"{source}: {message}")


def read_table(path: str | Path) -> pd.DataFrame:
    """The CSV's table, every cell a float; TrajectoryFileError for a file that is not one."""
    source = str(path)
    try:
        text = read_bounded_text(path, MAX_TRAJECTORY_CSV_BYTES, "trajectory CSV")
        frame = pd.read_csv(io.StringIO(text), dtype=str, keep_default_na=False)
    except FileRefused as error:
        raise TrajectoryFileError(str(error)) from None
    except OSError as error:
        raise _fail(source, f"cannot read: {error.strerror or error}") from None
    except (UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError) as error:
        raise _fail(source, f"not a CSV table: {str(error).splitlines()[0]}") from None
    if frame.empty:
        raise _fail(source, "has no rows")
    numbers = {}
    for column in frame.columns:
        values = np.empty(len(frame))
        for row, text in enumerate(frame[column]):
            values[row] = _number(source, f"column {column}, row {row + 1}", text)
        numbers[column] = values
    return pd.DataFrame(numbers)


def _number(source: str, where: str, text: str) -> float:
    """The cell's value; TrajectoryFileError for one that is not a plain finite CSV number within
    MAX_MAGNITUDE."""
    shown = text if len(text) <= 40 else text[:40] + "..."
    if not NUMBER.fullmatch(text.strip(" \t")):
        try:
            finite = math.isfinite(float(text))
        except ValueError:
            finite = True
        kind = "not a number" if finite else "not finite"
        raise _fail(source, f"{where}: {kind}: {shown!r} (a CSV number is digits, a point and an exponent)")
    value = float(text)
    if not abs(value) <= MAX_MAGNITUDE:
        raise _fail(
            source,
            f"{where}: {shown!r} is beyond the largest magnitude a trajectory may hold, {MAX_MAGNITUDE:g}",
        )
    return value


def check_columns(source: str, columns: list[str], scenario: Scenario) -> None:
    """Every column is `t`, a coordinate of one of the scenario's bodies, or one of its extras."""
    known = ["t", *extra_columns(scenario)]
    known += [f"{b}.{n}" for b in scenario.body_names for names in COLUMNS.values() for n in names]
    known += [f"{j.name}.{axis}" for j in scenario.joints for axis in ("fx", "fy")]  # for suggestions
    known += [f"{d.name}.force" for d in scenario.drivers]
    if "t" not in columns:
        raise _fail(source, "no column 't' (the time)")
    for column in columns:
        if column not in known and not is_extra(column, scenario):
            raise _fail(
                source,
                f"unknown column '{column}'{suggestion(column, known)}; {scenario.name} has the bodies "
                f"{', '.join(scenario.body_names)} (columns BODY.x BODY.y BODY.theta BODY.vx ... "
                "BODY.alpha; extras are named after its joints, drivers, forces or cams, or energy.*)",
            )


def check_grid(source: str, times: np.ndarray, scenario: Scenario) -> None:
    """The file's times are the scenario's grid, each within GRID_TOLERANCE * t_end."""
    grid = np.asarray(scenario.times())
    span = f"{len(grid)} times, {scenario.steps} steps from 0 to {scenario.t_end:.17g} s"
    if len(times) != len(grid):
        raise _fail(
            source,
            f"has {len(times)} time rows; the grid of {scenario.name} has {span} "
            "(--set changes the scenario's grid)",
        )
    off = np.abs(times - grid)
    bad = np.flatnonzero(off > GRID_TOLERANCE * scenario.t_end)
    if bad.size:
        first = int(bad[0])
        raise _fail(
            source,
            f"the times are not the grid of {scenario.name} ({span}): {bad.size} of {len(grid)} differ, "
            f"by up to {float(off.max()):.3g} s; the first at row {first + 1}: t = {times[first]:.17g}, "
            f"expected {grid[first]:.17g}",
        )


def _levels_of(source: str, columns: set[str], body: str) -> tuple[Level, ...]:
    """The levels the file has whole for `body`; a level with some of its columns only is refused."""
    whole = []
    for level, names in COLUMNS.items():
        present = [n for n in names if f"{body}.{n}" in columns]
        if present and len(present) < len(names):
            lacking = [f"{body}.{n}" for n in names if n not in present]
            raise _fail(
                source,
                f"body '{body}' has {', '.join(f'{body}.{n}' for n in present)} but not "
                f"{', '.join(lacking)}: the {level} level's three columns come together",
            )
        if present:
            whole.append(level)
    return tuple(whole)


def read_trajectory(path: str | Path, scenario: Scenario) -> ImportedTrajectory:
    """The trajectory in the CSV at `path`, checked against `scenario` (TrajectoryFileError)."""
    source = str(path)
    frame = read_table(path)
    columns = [str(c) for c in frame.columns]
    check_columns(source, columns, scenario)
    check_grid(source, frame["t"].to_numpy(), scenario)
    present = set(columns)
    levels = {b: _levels_of(source, present, b) for b in scenario.body_names}
    outputs = scenario.output_bodies
    bodies = tuple(b for b in outputs if levels[b])
    if not bodies:
        raise _fail(source, f"has no column of the output bodies of {scenario.name}: {', '.join(outputs)}")
    notes = []
    missing = tuple(b for b in outputs if b not in bodies)
    if missing:
        notes.append(f"bodies not in the file, not scored: {', '.join(missing)}")
    ignored = [b for b in scenario.body_names if levels[b] and b not in outputs]
    if ignored:
        notes.append(f"not outputs of {scenario.name}, not scored: {', '.join(ignored)}")
    kept = tuple(lv for lv in LEVELS if all(lv in levels[b] for b in bodies))
    for level in LEVELS:
        if level not in kept and level in scenario.levels:
            lacking = [b for b in bodies if level not in levels[b]]
            notes.append(f"{level} not in the file for {', '.join(lacking)}: not scored")
    arrays = {
        lv: np.stack([frame[[f"{b}.{n}" for n in COLUMNS[lv]]].to_numpy() for b in bodies], axis=1)
        for lv in kept
    }
    extras = {c: frame[c].to_numpy() for c in columns if c != "t" and is_extra(c, scenario)}
    grid = np.asarray(scenario.times(), dtype=float)  # the scenario's exact grid, checked above
    trajectory = Trajectory(grid, bodies, extras=extras, **arrays)  # type: ignore[arg-type]
    missing_levels = tuple(lv for lv in scenario.levels if lv not in kept)
    return ImportedTrajectory(source, trajectory, missing, missing_levels, tuple(notes))
