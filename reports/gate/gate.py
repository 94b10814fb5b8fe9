"""The regression gate: results compared cell by cell with a committed baseline.

A cell is one scenario x engine at the engine's default setting, or one ladder setting (matched by
its label). A cell regresses when its status gets worse (ok, then unsupported, then any failure),
or when both runs are ok and its headline error exceeds `factor` times the baseline's; errors below
ERROR_FLOOR count as ERROR_FLOOR, so round-off near machine precision does not trip the gate.
Baseline cells of a scenario-engine pair the current results cover but lack are regressions too;
ladder settings the current results did not run (a quick subset) are not compared. Run times are
not gated: they depend on the machine.

An optional engine (an extra such as Drake) may be installed on one machine and not on another, so
the gate says once per engine what it did not judge, never a failure per cell: the cells of an
engine the baseline has none of are new (listed, not gated, until `--update` adds them), and the
baseline's cells of an engine the run could not load (not installed) are not compared.

Every level is compared, keyed per level: the `error_position`, `error_velocity` and
`error_acceleration` columns (a column a results table lacks is a level not produced; a level
absent from both sides is not compared; a baseline from before the per-level columns has its
headline `error` as the position level). The gate cannot pass by accident: a baseline that is not
a well-formed list of cells, an `ok` cell without a finite error, a results table with cells the
baseline lacks (of an engine it has cells of), and a comparison of 0 cells are errors (GateError:
bad input, exit 2).
"""

from __future__ import annotations

import json
import math
import os
from collections import Counter
from collections.abc import Collection
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from reports.store import SCHEMA_VERSION, atomic_output, output_target
from scenarios.files.bounded_read import MAX_BASELINE_BYTES, read_bounded_text

if TYPE_CHECKING:  # frames are handed in; the command line imports the gate without pandas
    import pandas as pd

DEFAULT_FACTOR = 10.0
ERROR_FLOOR = 1e-12
RANK = {"ok": 0, "unsupported": 1}  # every failure status ranks 2
DEFAULT = "(default)"
LEVELS = ("position", "velocity", "acceleration")
LEVEL_FIELDS = tuple(f"error_{level}" for level in LEVELS)
CELL_FIELDS = ("scenario", "engine", "setting", "is_default", "status", "error", "message")


class GateError(ValueError):
    """A baseline or a comparison the gate cannot trust: bad input, never a pass."""


@dataclass(frozen=True)
class Regression:
    scenario: str
    engine: str
    setting: str
    what: str

    def __str__(self) -> str:
        return f"{self.scenario} x {self.engine} [{self.setting}]: {self.what}"


@dataclass(frozen=True)
class Cell:
    """One cell the gate looked at: its status now (`missing` for a default row the results lack)
    and the baseline's, each level's error now and in the baseline, and what regressed ('' if
    nothing did)."""

    scenario: str
    engine: str
    setting: str
    status: str
    baseline_status: str
    errors: tuple[tuple[str, float | None, float | None], ...]
    what: str


@dataclass(frozen=True)
class GateResult:
    compared: int
    regressions: tuple[Regression, ...]
    cells: tuple[Cell, ...] = ()
    """Every cell compared and every missing one, in the baseline's order (for --junit, --json)."""
    new: tuple[tuple[str, int], ...] = ()
    """(engine, cells) of the engines the baseline has no cell of: run, not gated."""
    not_installed: tuple[tuple[str, int], ...] = ()
    """(engine, baseline cells) of the baseline's engines not installed where the results were made."""

    @property
    def passed(self) -> bool:
        return not self.regressions


def baseline_cells(frame: pd.DataFrame) -> list[dict[str, Any]]:
    """The cells of a results table, as stored in a baseline file."""
    cells = []
    for row in frame.sort_values(["scenario", "engine", "setting"]).to_dict("records"):
        cell = {k: row[k] for k in CELL_FIELDS}
        cell["is_default"] = bool(cell["is_default"])
        for name in ("error", *LEVEL_FIELDS):
            value = row.get(name)
            if name in cell or name in frame.columns:
                cell[name] = None if _nan(value) else float(value)
        cells.append(cell)
    return cells


def write_baseline(path: str | os.PathLike[str], frame: pd.DataFrame, meta: dict[str, Any]) -> None:
    _write_cells(path, baseline_cells(frame), meta)


def _write_cells(path: str | os.PathLike[str], cells: list[dict[str, Any]], meta: dict[str, Any]) -> None:
    keep = ("suite", "git_revision", "date", "engines", "machine", "python")
    head = {"schema_version": SCHEMA_VERSION, "made_from": {k: meta.get(k) for k in keep}}
    lines = ",\n".join(json.dumps(c, sort_keys=True) for c in cells)
    text = json.dumps(head, indent=1, sort_keys=True)[:-2]  # one cell a line, for readable diffs
    with atomic_output(path) as stream:  # a failed write leaves the old baseline as it was
        stream.write(f'{text},\n "cells": [\n{lines}\n ]\n}}\n')


def read_baseline(path: str | os.PathLike[str]) -> list[dict[str, Any]]:
    """The cells of a baseline file, each checked; GateError naming the first that is not sound."""
    try:
        # every number as a float: a 400-digit integer becomes inf (refused as unsound), never an
        # int that overflows a comparison or trips Python's limit on digits
        document = json.loads(read_bounded_text(path, MAX_BASELINE_BYTES, "baseline"), parse_int=float)
    except (OSError, ValueError) as error:  # FileRefused among them
        raise GateError(f"baseline {path} cannot be read: {str(error)[:300]}") from None
    except RecursionError:
        raise GateError(f"baseline {path} cannot be read: nested too deeply") from None
    if not isinstance(document, dict) or document.get("schema_version") != SCHEMA_VERSION:
        version = document.get("schema_version") if isinstance(document, dict) else None
        raise GateError(f"baseline {path} has schema version {version}, expected {SCHEMA_VERSION}")
    cells = document.get("cells")
    if not isinstance(cells, list) or not cells:
        raise GateError(f"baseline {path}: 'cells' must be a non-empty list")
    for number, cell in enumerate(cells):
        problem = _unsound(cell)
        if problem:
            raise GateError(
                f"baseline {path}, cell {number}: {problem}; regenerate it with `mbxval check --update`"
            )
    return cells


def _unsound(cell: Any) -> str:
    if not isinstance(cell, dict):
        return "not an object"
    for name in ("scenario", "engine", "setting", "status"):
        if not isinstance(cell.get(name), str):
            return f"'{name}' must be a string"
    if not isinstance(cell.get("is_default"), bool):
        return "'is_default' must be true or false"
    for name in ("error", *LEVEL_FIELDS):
        value = cell.get(name)
        if value is not None and (isinstance(value, bool) or not isinstance(value, int | float)):
            return f"'{name}' must be a number or null, got {value!r}"
        if value is not None and not (math.isfinite(value) and value >= 0):
            return f"'{name}' must be finite and not negative, got {value}"
    if cell["status"] == "ok" and cell.get("error") is None:
        return "an ok cell without an error cannot fail: it would pass anything"
    return ""


def judge(
    baseline: list[dict[str, Any]],
    current: pd.DataFrame,
    factor: float = DEFAULT_FACTOR,
    not_installed: Collection[str] = (),
) -> GateResult:
    """Every regression of `current` (a results table) against the `baseline` cells; GateError
    when the baseline lacks cells of the results (of an engine it knows) or nothing is compared.
    `not_installed`: the engines the run could not load because their package is absent."""
    if not (math.isfinite(factor) and factor > 0):
        raise GateError(f"the error factor must be a finite positive number, got {factor}")
    index = {_key(c): c for c in baseline_cells(current)}
    known = {_key(c) for c in baseline}
    engines = {c["engine"] for c in baseline}
    unjudged = Counter(k[1] for k in index if k[1] not in engines)
    index = {k: c for k, c in index.items() if k[1] in engines}
    run = set(current["scenario"])
    absent = Counter(
        c["engine"] for c in baseline if c["engine"] in set(not_installed) and c["scenario"] in run
    )
    unknown = sorted(k for k in index if k not in known)
    if unknown:
        example = " x ".join(unknown[0])
        raise GateError(
            f"the baseline lacks {len(unknown)} of the {len(index)} cells of the results "
            f"(such as {example}): it is older or smaller than what was run; update it with --update"
        )
    covered = set(zip(current["scenario"], current["engine"], strict=True))
    regressions, cells, compared = [], [], 0
    for old in baseline:
        new = index.get(_key(old))
        label = DEFAULT if old["is_default"] else old["setting"]
        if new is None:
            if old["is_default"] and (old["scenario"], old["engine"]) in covered:
                what = f"missing: no default-setting row (baseline: {old['status']})"
                regressions.append(Regression(old["scenario"], old["engine"], label, what))
                cells.append(_cell(old, None, label, what))
            continue
        compared += 1
        what = _worse(old, new, factor)
        if what:
            regressions.append(Regression(old["scenario"], old["engine"], label, what))
        cells.append(_cell(old, new, label, what))
    if compared == 0:
        raise GateError("0 cells compared: the results and the baseline have no cell in common")
    return GateResult(
        compared,
        tuple(regressions),
        tuple(cells),
        tuple(sorted(unjudged.items())),
        tuple(sorted(absent.items())),
    )


def _cell(old: dict[str, Any], new: dict[str, Any] | None, label: str, what: str) -> Cell:
    before, after = level_errors(old), level_errors(new or {})
    errors = tuple((level, after[level], before[level]) for level in LEVELS)
    status = "missing" if new is None else new["status"]
    return Cell(old["scenario"], old["engine"], label, status, old["status"], errors, what)


def level_errors(cell: dict[str, Any]) -> dict[str, float | None]:
    """The cell's error per level (a baseline from before the level columns: `error` is position)."""
    errors: dict[str, float | None] = {level: cell.get(f"error_{level}") for level in LEVELS}
    if not any(f"error_{level}" in cell for level in LEVELS):
        errors["position"] = cell.get("error")
    return errors


def _worse(old: dict[str, Any], new: dict[str, Any], factor: float) -> str:
    if _rank(new["status"]) > _rank(old["status"]):
        return f"status {old['status']} -> {new['status']}: {new['message']}".rstrip(": ")
    if old["status"] != "ok" or new["status"] != "ok":
        return ""
    before, after = level_errors(old), level_errors(new)
    problems = []
    for level in LEVELS:
        was, now = before[level], after[level]
        if was is None:
            continue  # not produced in the baseline: nothing to hold the results to
        if now is None:
            problems.append(f"{level} error no longer measured (baseline {was:.3g})")
        elif now > factor * max(was, ERROR_FLOOR):
            problems.append(f"{level} error {now:.3g} > {factor:g} x baseline {was:.3g}")
    return "; ".join(problems)


def _key(cell: dict[str, Any]) -> tuple[str, str, str]:
    return (cell["scenario"], cell["engine"], DEFAULT if cell["is_default"] else cell["setting"])


def _rank(status: str) -> int:
    return RANK.get(status, 2)


def _nan(value: Any) -> bool:
    return value is None or (isinstance(value, float) and math.isnan(value))


KEY_FIELDS = ("scenario", "engine", "setting", "is_default")


def updatable_cells(path: str | os.PathLike[str]) -> list[dict[str, Any]]:
    """The cells of the baseline that `check --update` would replace at `path`: none for a new
    path; GateError for a file that is not a baseline (a JSON object with a schema_version and a
    list of cells, each naming its scenario, engine and setting), which --update never overwrites,
    and OutputRefused for a path that is not a regular file."""
    if not os.path.exists(output_target(path)):  # a FIFO or a device is refused before it is read
        return []
    try:
        document = json.loads(read_bounded_text(path, MAX_BASELINE_BYTES, "baseline"))
    except (OSError, ValueError, RecursionError):  # FileRefused among them
        document = None
    cells = document.get("cells") if isinstance(document, dict) and "schema_version" in document else None
    if not (isinstance(cells, list) and cells and all(_keyed(c) for c in cells)):
        raise GateError(
            f"--baseline {path} is not a baseline (a JSON object with a schema_version and a list of "
            "cells): --update writes only a baseline or a new file; nothing was written"
        )
    return cells


def _keyed(cell: object) -> bool:
    return isinstance(cell, dict) and all(name in cell for name in KEY_FIELDS)


def update_baseline(
    path: str | os.PathLike[str],
    frame: pd.DataFrame,
    meta: dict[str, Any],
    not_installed: Collection[str] = (),
) -> str:
    """Write the baseline from the results and say what it adds, drops and changes; the cells of
    the engines `not_installed` here are kept as they were (a machine without an optional engine
    does not drop its cells)."""
    before = {_key(c): c for c in updatable_cells(path)}
    cells = baseline_cells(frame)
    kept = [c for c in before.values() if c["engine"] in set(not_installed)]
    for cell in cells:  # never write a baseline that `check` would refuse
        problem = _unsound(cell)
        if problem:
            raise GateError(
                f"cannot write baseline {path}: row {' x '.join(_key(cell))}: {problem} "
                "(check would refuse it); rerun that row, or leave it out with --scenario/--engine"
            )
    cells = sorted([*cells, *kept], key=lambda c: (c["scenario"], c["engine"], c["setting"]))
    after = {_key(c): c for c in cells}
    added = sorted(k for k in after if k not in before)
    dropped = sorted(k for k in before if k not in after)
    changed = sorted(k for k in after if k in before and _moved(before[k], after[k]))
    _write_cells(path, cells, meta)
    lines = [
        f"wrote baseline {path}: {len(after)} cells (was {len(before)}): "
        f"{len(added)} added, {len(dropped)} dropped, {len(changed)} changed"
    ]
    lines += [
        f"  kept the {n} cells of {engine} as they were: {engine} is not installed here"
        for engine, n in sorted(Counter(c["engine"] for c in kept).items())
    ]
    for sign, keys in (("+", added), ("-", dropped), ("~", changed)):
        lines += [f"  {sign} {' x '.join(k)}" + _change(before, after, k, sign) for k in keys]
    return "\n".join(lines)


def _moved(old: dict[str, Any], new: dict[str, Any]) -> bool:
    return old.get("status") != new.get("status") or level_errors(old) != level_errors(new)


def _change(before: dict[Any, Any], after: dict[Any, Any], key: Any, sign: str) -> str:
    if sign != "~":
        return ""
    old, new = before[key], after[key]
    return f": {old.get('status')} {old.get('error')} -> {new.get('status')} {new.get('error')}"


def describe(result: GateResult, baseline: str, factor: float) -> str:
    """The readable result: one line, or a header and one line per regression; then one line per
    engine the gate did not judge (new to the baseline, or not installed here)."""
    head = f"check against {baseline} (error factor {factor:g}): {result.compared} cells compared"
    if result.passed:
        lines = [f"{head}, no regressions"]
    else:
        lines = [f"{head}, {len(result.regressions)} regressions:"]
        lines += [f"  - {r}" for r in result.regressions]
    lines += [
        f"{engine} not installed: its {n} baseline cells not compared" for engine, n in result.not_installed
    ]
    lines += [
        f"{engine}: {n} new cells, not in the baseline, not gated (--update adds them)"
        for engine, n in result.new
    ]
    return "\n".join(lines)
