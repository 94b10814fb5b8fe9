"""Building the tidy result rows (columns declared in columns.py) from what became of a run."""

from __future__ import annotations

import functools
import json
import math
import socket
from typing import Any

import adapters
from adapters.base import RunResult, Setting, Status
from reports.scoring import characteristic_rate, lost, self_check
from reports.store import NOT_RUN, empty_row, provenance, scenario_identity
from scenarios import catalogue
from scenarios.kept import kept
from scenarios.scenario import Scenario


def base_row(
    scenario: Scenario, engine: str, version: str, setting: Setting | None, is_default: bool
) -> dict[str, Any]:
    """A row with the identity filled in and every measurement empty."""
    row = empty_row()
    row.update(
        scenario=scenario.name,
        family=scenario.family,
        variant=scenario.variant,
        sweep=json.dumps(dict(scenario.point)) if scenario.point else "",
        scenario_digest=scenario_digest(scenario),
        engine=engine,
        engine_version=version,
        mode=setting.mode if setting else "",
        setting=setting.label if setting else NOT_RUN,
        options=json.dumps(dict(setting.options) if setting else {}, sort_keys=True),
        is_default=is_default,
        grid_points=scenario.steps + 1,
        t_end=scenario.t_end,
        characteristic_length=scenario.characteristic_length,
        characteristic_rate=characteristic_rate(scenario),
        host=socket.gethostname(),
        recorded_at=provenance.now(),
        **ranks(scenario.name, engine),
    )
    return row


@kept(maxsize=64)
def scenario_digest(scenario: Scenario) -> str:
    """scenarios.identity.digest, once per scenario (every row of a scenario states
    it, and a file's text is hashed each time; equal scenarios have the same digest)."""
    return scenario_identity.digest(scenario)


def ranks(scenario: str, engine: str) -> dict[str, int]:
    """The row's scenario_rank and engine_rank: where the report lists it."""
    listed, engines = _orders(tuple(adapters.ENGINES))
    return {"scenario_rank": _rank(scenario, listed), "engine_rank": _rank(engine, engines)}


@functools.cache
def _orders(registry: tuple[str, ...]) -> tuple[list[str], list[str]]:
    """The report's orders of scenarios and engines, read once per process and registry (the
    installed engines' entry points cost milliseconds to read: once per row was a third of a
    sweep run's overhead)."""
    return catalogue(include_stress=True, include_dynamic=True), adapters.names()


def _rank(name: str, order: list[str]) -> int:
    """`name`'s place in `order` (the report lists by it), -1 where it is not listed."""
    return order.index(name) if name in order else -1


def failure_row(
    scenario: Scenario,
    engine: str,
    version: str,
    setting: Setting | None,
    is_default: bool,
    status: Status,
    message: str,
) -> dict[str, Any]:
    """A row for a run that produced nothing to compare."""
    row = base_row(scenario, engine, version, setting, is_default)
    row.update(status=status, message=message)
    return row


def result_row(
    scenario: Scenario,
    result: RunResult,
    is_default: bool,
    repeats: int,
    warmup: int,
    metrics: dict[str, float],
    levels: tuple[str, ...],
    note: str = "",
) -> dict[str, Any]:
    """A row for a run that reached the adapter: its status, timings and (when ok) its errors."""
    row = base_row(scenario, result.engine, result.version, result.setting, is_default)
    row.update(
        status=result.status,
        measures=result.measures,
        message="; ".join(m for m in (result.message, note) if m),
        failure_time=math.nan if result.failure_time is None else result.failure_time,
        warnings=" | ".join(result.warnings),
        build_time=result.build_time,
        run_time=result.run_time,
        warmup_time=result.warmup_time,
        repeats_time=result.repeats_time,
        build_time_wall=result.build_time_wall,
        run_time_wall=result.run_time_wall,
        warmup_time_wall=result.warmup_time_wall,
        repeats_time_wall=result.repeats_time_wall,
        steps=result.steps,
        repeats=repeats if result.status == "ok" else 0,
        warmup=warmup if result.status == "ok" else 0,
        levels=",".join(levels),
    )
    row.update(metrics)
    gone = lost(scenario, metrics) if result.status == "ok" else ""
    if gone:  # ok by the engine, off by more than the mechanism's size from the truth
        row.update(status="diverged", message="; ".join(m for m in (gone, row["message"]) if m))
    elif result.status == "ok":  # an ok run that drifted says so, by its own figures
        residual, energy = (
            metrics.get("constraint_residual", math.nan),
            metrics.get("energy_change", math.nan),
        )
        halving = metrics.get("step_halving", math.nan)
        row["self_check"] = self_check.verdict(residual, energy, halving)
    return row
