"""The gate's verdict as files CI systems read: JUnit XML (one test case per compared cell, a failure
per regression with its errors against the baseline and the factor allowed) and JSON (the same
cells, for other tools). Written whole or not at all (atomic_output)."""

from __future__ import annotations

import json
import os
import xml.etree.ElementTree as ET
from typing import Any

from reports.gate.gate import ERROR_FLOOR, Cell, GateResult
from reports.store import atomic_output

SUITE = "mbxval check"


def _growth(now: float | None, was: float | None) -> float | None:
    """How many times the baseline's error the error is now, each at least the gate's floor (as the
    gate compares them); None where either is missing."""
    if now is None or was is None:
        return None
    return max(now, ERROR_FLOOR) / max(was, ERROR_FLOOR)


def cell_lines(cell: Cell) -> list[str]:
    """The cell's status and each level's error against the baseline, one line each."""
    lines = [f"status {cell.status} (baseline {cell.baseline_status})"]
    for level, now, was in cell.errors:
        if now is None and was is None:
            continue
        growth = _growth(now, was)
        times = "" if growth is None else f", x{growth:.3g} the baseline's"
        lines.append(f"{level} error {_number(now)} (baseline {_number(was)}{times})")
    return lines


def _number(value: float | None) -> str:
    return "not measured" if value is None else f"{value:.3g}"


def junit_xml(result: GateResult, baseline: str, factor: float) -> str:
    """The JUnit XML document: one <testsuite>, a <testcase> per cell (classname the scenario,
    name the engine and setting), a <failure> for each regression."""
    failures = sum(1 for c in result.cells if c.what)
    suites = ET.Element("testsuites", name=SUITE, tests=str(len(result.cells)), failures=str(failures))
    suite = ET.SubElement(
        suites, "testsuite", name=SUITE, tests=str(len(result.cells)), failures=str(failures), errors="0"
    )
    properties = ET.SubElement(suite, "properties")
    ET.SubElement(properties, "property", name="baseline", value=baseline)
    ET.SubElement(properties, "property", name="factor", value=f"{factor:g}")
    for engine, n in result.not_installed:
        ET.SubElement(
            properties, "property", name=f"not installed: {engine}", value=f"{n} cells not compared"
        )
    for engine, n in result.new:
        ET.SubElement(properties, "property", name=f"new: {engine}", value=f"{n} cells not gated")
    for cell in result.cells:
        case = ET.SubElement(
            suite, "testcase", classname=cell.scenario, name=f"{cell.engine} [{cell.setting}]"
        )
        text = "\n".join([*cell_lines(cell), f"allowed: {factor:g} x the baseline's error"])
        if cell.what:
            failure = ET.SubElement(case, "failure", message=cell.what, type="regression")
            failure.text = text
        else:
            ET.SubElement(case, "system-out").text = text
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n"


def verdict_json(result: GateResult, baseline: str, factor: float) -> str:
    """The JSON document: the verdict, then every cell with its errors and the baseline's."""
    cells: list[dict[str, Any]] = []
    for cell in result.cells:
        errors = {
            level: {"error": now, "baseline": was, "growth": _growth(now, was)}
            for level, now, was in cell.errors
            if now is not None or was is not None
        }
        cells.append(
            {
                "scenario": cell.scenario,
                "engine": cell.engine,
                "setting": cell.setting,
                "status": cell.status,
                "baseline_status": cell.baseline_status,
                "passed": not cell.what,
                "regression": cell.what or None,
                "errors": errors,
            }
        )
    document = {
        "baseline": baseline,
        "factor": factor,
        "passed": result.passed,
        "compared": result.compared,
        "regressions": len(result.regressions),
        "new": dict(result.new),
        "not_installed": dict(result.not_installed),
        "cells": cells,
    }
    return json.dumps(document, indent=1) + "\n"


def write(path: str | os.PathLike[str], text: str) -> None:
    with atomic_output(path) as stream:
        stream.write(text)
