"""A trajectory made by another tool, read from the canonical CSV (scenarios.trajectory) and checked
against the scenario it claims to solve, before anything is scored or stored.

The file has the column `t`, then `<body>.x <body>.y <body>.theta` (position), `.vx .vy .omega`
(velocity), `.ax .ay .alpha` (acceleration) per body, and optionally the extra columns an engine
writes for the scenario, kept but not scored: a cam's contact angle `<cam>.phi`, angle outputs,
`<joint>.fx` and `<driver>.force` (reactions and driving forces, named after the scenario's own
joints, drivers and forces) and `energy.*`. Bodies and levels may be missing: a level is scored when every
scored body has it, and what is left out is said. Refused, with a TrajectoryFileError naming the
file and the line and column, never what the file says (it may be any file a user names): an
unreadable file, an unknown column, a body's level with some of its three columns only, a
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


def read_text(path: str | Path) -> str:
    """The file's text, within its size limit; TrajectoryFileError for a file that cannot be read."""
    try:
        return read_bounded_text(path, MAX_TRAJECTORY_CSV_BYTES, "trajectory CSV")
    except FileRefused as error:
        raise TrajectoryFileError(str(error)) from None
    except OSError as error:
        raise _fail(str(path), f"cannot read: {error.strerror or error}") from None


def parse_table(text: str, source: str) -> pd.DataFrame:
    """The CSV's cells as text, under its header; TrajectoryFileError for text that is not a table
    (pandas' tokenizer says where, never what: its messages quote no field)."""
    try:
        frame = pd.read_csv(io.StringIO(text), dtype=str, keep_default_na=False)
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as error:
        raise _fail(source, f"not a CSV table: {str(error).splitlines()[0]}") from None
    if frame.empty:
        raise _fail(source, "has no rows")
    return frame


def _lines(text: str) -> list[int]:
    """The line numbers (from 1) of the text's lines that are not blank: the header's, then each
    row's, as the CSV reader skips blank lines."""
    return [k for k, line in enumerate(re.split(r"\r\n|\r|\n", text), 1) if line.strip(" \t")]


def numbers(frame: pd.DataFrame, text: str, source: str) -> pd.DataFrame:
    """Every cell as a float; TrajectoryFileError naming the line and column of the first that is
    not a plain finite CSV number within MAX_MAGNITUDE."""
    values = {}
    for place, column in enumerate(frame.columns):
        column_values = np.empty(len(frame))
        for row, cell in enumerate(frame[column]):
            problem = _problem(cell)
            if problem:
                raise _fail(source, f"{_where(text, row)}, column {place + 1}: {problem}")
            column_values[row] = float(cell)
        values[column] = column_values
    return pd.DataFrame(values)


def _where(text: str, row: int) -> str:
    """Where data row `row` (from 0) is in the text: its line, as the CSV reader skips blank lines."""
    lines = _lines(text)
    return f"line {lines[row + 1]}" if row + 1 < len(lines) else f"row {row + 1}"


def _problem(text: str) -> str:
    """What kind of cell `text` is when it is not a plain finite CSV number within MAX_MAGNITUDE
    (never what it says); '' for a good one."""
    if not NUMBER.fullmatch(text.strip(" \t")):
        try:
            kind = "not a number" if math.isfinite(float(text)) else "not finite"
        except ValueError:
            kind = "empty" if not text.strip() else "not a number"
        return f"{kind}; expected a finite number (digits, a point and an exponent)"
    if not abs(float(text)) <= MAX_MAGNITUDE:
        return f"beyond the largest magnitude a trajectory may hold, {MAX_MAGNITUDE:g}"
    return ""


def check_columns(source: str, columns: list[str], scenario: Scenario) -> None:
    """Every column is `t`, a coordinate of one of the scenario's bodies, or one of its extras."""
    known = ["t", *extra_columns(scenario)]
    known += [f"{b}.{n}" for b in scenario.body_names for names in COLUMNS.values() for n in names]
    known += [f"{j.name}.{axis}" for j in scenario.joints for axis in ("fx", "fy")]  # for suggestions
    known += [f"{d.name}.force" for d in scenario.drivers]
    for place, column in enumerate(columns, 1):
        if column not in known and not is_extra(column, scenario):
            raise _fail(
                source,
                f"line 1, column {place}: not a column name of {scenario.name}{suggestion(column, known)}; "
                f"expected t, then the bodies "
                f"{', '.join(scenario.body_names)} (columns BODY.x BODY.y BODY.theta BODY.vx ... "
                "BODY.alpha; extras are named after its joints, drivers, forces or cams, or energy.*)",
            )
    if "t" not in columns:
        raise _fail(source, "no column 't' (the time)")


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
    return parse_trajectory(read_text(path), str(path), scenario)


def parse_trajectory(text: str, source: str, scenario: Scenario) -> ImportedTrajectory:
    """The trajectory in CSV `text` (named `source` in messages), checked against `scenario`: its
    header first, so that a message names a column only once it is known to be a column name."""
    table = parse_table(text, source)
    columns = [str(c) for c in table.columns]
    check_columns(source, columns, scenario)
    frame = numbers(table, text, source)
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
