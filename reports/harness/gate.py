"""The regression gate: results compared cell by cell with a committed baseline.

A cell is one scenario x engine at the engine's default setting, or one sweep setting (matched by
its label). A cell regresses when its status gets worse (ok, then unsupported, then any failure),
or when both runs are ok and its headline error exceeds `factor` times the baseline's; errors below
ERROR_FLOOR count as ERROR_FLOOR, so round-off near machine precision does not trip the gate.
Baseline cells of a scenario-engine pair the current results cover but lack are regressions too;
sweep settings the current results did not run (a quick subset) are not compared. Run times are
not gated: they depend on the machine.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from reports.harness.results_store import SCHEMA_VERSION

DEFAULT_FACTOR = 10.0
ERROR_FLOOR = 1e-12
RANK = {"ok": 0, "unsupported": 1}  # every failure status ranks 2
DEFAULT = "(default)"
CELL_FIELDS = ("scenario", "engine", "setting", "is_default", "status", "error", "message")


@dataclass(frozen=True)
class Regression:
    scenario: str
    engine: str
    setting: str
    what: str

    def __str__(self) -> str:
        return f"{self.scenario} x {self.engine} [{self.setting}]: {self.what}"


@dataclass(frozen=True)
class GateResult:
    compared: int
    regressions: tuple[Regression, ...]

    @property
    def passed(self) -> bool:
        return not self.regressions


def baseline_cells(frame: pd.DataFrame) -> list[dict[str, Any]]:
    """The cells of a results table, as stored in a baseline file."""
    cells = []
    for row in frame.sort_values(["scenario", "engine", "setting"]).to_dict("records"):
        cell = {k: row[k] for k in CELL_FIELDS}
        cell["is_default"] = bool(cell["is_default"])
        cell["error"] = None if _nan(cell["error"]) else float(cell["error"])
        cells.append(cell)
    return cells


def write_baseline(path: str | os.PathLike[str], frame: pd.DataFrame, meta: dict[str, Any]) -> None:
    keep = ("suite", "git_revision", "date", "engines", "machine", "python")
    head = {"schema_version": SCHEMA_VERSION, "made_from": {k: meta.get(k) for k in keep}}
    cells = ",\n".join(json.dumps(c, sort_keys=True) for c in baseline_cells(frame))
    text = json.dumps(head, indent=1, sort_keys=True)[:-2]  # one cell a line, for readable diffs
    Path(path).write_text(f'{text},\n "cells": [\n{cells}\n ]\n}}\n')


def read_baseline(path: str | os.PathLike[str]) -> list[dict[str, Any]]:
    document = json.loads(Path(path).read_text())
    if document.get("schema_version") != SCHEMA_VERSION:
        raise ValueError(f"baseline {path} has schema version {document.get('schema_version')}")
    cells: list[dict[str, Any]] = document["cells"]
    return cells


def compare(
    baseline: list[dict[str, Any]], current: pd.DataFrame, factor: float = DEFAULT_FACTOR
) -> GateResult:
    """Every regression of `current` (a results table) against the `baseline` cells."""
    index = {_key(c): c for c in baseline_cells(current)}
    covered = set(zip(current["scenario"], current["engine"], strict=True))
    regressions, compared = [], 0
    for old in baseline:
        new = index.get(_key(old))
        label = DEFAULT if old["is_default"] else old["setting"]
        if new is None:
            if old["is_default"] and (old["scenario"], old["engine"]) in covered:
                what = f"missing: no default-setting row (baseline: {old['status']})"
                regressions.append(Regression(old["scenario"], old["engine"], label, what))
            continue
        compared += 1
        what = _worse(old, new, factor)
        if what:
            regressions.append(Regression(old["scenario"], old["engine"], label, what))
    return GateResult(compared, tuple(regressions))


def _worse(old: dict[str, Any], new: dict[str, Any], factor: float) -> str:
    if _rank(new["status"]) > _rank(old["status"]):
        return f"status {old['status']} -> {new['status']}: {new['message']}".rstrip(": ")
    if old["status"] != "ok" or new["status"] != "ok" or old["error"] is None:
        return ""
    if new["error"] is None:
        return f"error no longer measured (baseline {old['error']:.3g}): {new['message']}"
    allowed = factor * max(old["error"], ERROR_FLOOR)
    if new["error"] > allowed:
        return f"error {new['error']:.3g} > {factor:g} x baseline {old['error']:.3g}"
    return ""


def _key(cell: dict[str, Any]) -> tuple[str, str, str]:
    return (cell["scenario"], cell["engine"], DEFAULT if cell["is_default"] else cell["setting"])


def _rank(status: str) -> int:
    return RANK.get(status, 2)


def _nan(value: Any) -> bool:
    return value is None or (isinstance(value, float) and math.isnan(value))


def describe(result: GateResult, baseline: str, factor: float) -> str:
    """The readable result: one line, or a header and one line per regression."""
    head = f"check against {baseline} (error factor {factor:g}): {result.compared} cells compared"
    if result.passed:
        return f"{head}, no regressions"
    lines = [f"{head}, {len(result.regressions)} regressions:"]
    lines += [f"  - {r}" for r in result.regressions]
    return "\n".join(lines)
