"""What a report draws of every run, measured when the suite finishes and stored with the results,
so that the report reads it and never measures:
- each default run's dimensionless error at every grid time and level against the stored truth
  (reports.scoring.level_error.level_series), as extras of its stored trajectory (ERROR_SERIES);
- per scenario, the engines' default runs' widest difference at each level and the pair that
  differs so (reports.scoring.agreement), as JSON in the `agreement` column of the scenario's rows;
- the ranks that order the report (rows.ranks), in rows stored before they were recorded.
The agreement depends on which engines' runs the store holds, so it is measured again at every
finish (a row is rewritten only where it changed); an error series, once stored, is kept.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping
from typing import Any

import numpy as np

from reports.run.rows import ranks
from reports.scoring import level_series, pair_differences, widest
from reports.store import ERROR_SERIES, TRUTH, Key, ResultsStore, stored_truths
from scenarios.scenario import LEVELS
from scenarios.trajectory import Trajectory


def record(store: ResultsStore) -> int:
    """Store the error series and the agreement `store` lacks or holds out of date (the caller
    saves); returns how many trajectories and rows were written."""
    scales = _scales(store.rows.values())
    return _record_series(store, scales) + _record_agreement(store, scales) + _record_ranks(store)


def _scales(rows: Any) -> dict[str, tuple[float, float]]:
    """Each scenario's characteristic length and rate, as its rows stored them."""
    found: dict[str, tuple[float, float]] = {}
    for row in rows:
        found.setdefault(
            str(row["scenario"]), (float(row["characteristic_length"]), float(row["characteristic_rate"]))
        )
    return found


def _runs(trajectories: Mapping[Key, Trajectory]) -> dict[str, dict[str, Trajectory]]:
    """The stored runs (each engine's default) of every scenario, by engine."""
    runs: dict[str, dict[str, Trajectory]] = {}
    for (scenario, engine, _), trajectory in trajectories.items():
        if engine != TRUTH:
            runs.setdefault(scenario, {})[engine] = trajectory
    return runs


def _record_series(store: ResultsStore, scales: dict[str, tuple[float, float]]) -> int:
    truths = stored_truths(store.trajectories)
    done = 0
    for key, run in list(store.trajectories.items()):
        scenario, engine, _ = key
        truth = truths.get(scenario)
        if (
            engine == TRUTH
            or truth is None
            or scenario not in scales
            or not set(truth.bodies) <= set(run.bodies)
        ):
            continue
        if any(name in run.extras for name in ERROR_SERIES.values()):
            continue
        series = {
            name: level_series(run, truth, level, *scales[scenario]) for level, name in ERROR_SERIES.items()
        }
        extras = {name: np.asarray(s, dtype=float) for name, s in series.items() if s is not None}
        if extras:
            store.trajectories[key] = dataclasses.replace(run, extras={**run.extras, **extras})
            done += 1
    return done


def agreement(runs: Mapping[str, Trajectory], length: float, rate: float) -> str:
    """The widest difference at each level among `runs` and its pair, as the column stores it:
    {"engines": n, "levels": {level: [engine a, engine b, value] or null}}."""
    pairs = pair_differences(runs, length, rate)
    levels: dict[str, list[Any] | None] = {}
    for level in LEVELS:
        pair, value = widest(pairs, level)
        levels[level] = None if pair is None else [pair[0], pair[1], value]
    return json.dumps({"engines": len(runs), "levels": levels})


def _record_agreement(store: ResultsStore, scales: dict[str, tuple[float, float]]) -> int:
    runs = _runs(store.trajectories)
    measured = {
        s: agreement(found, *scales[s]) for s, found in runs.items() if len(found) >= 2 and s in scales
    }
    done = 0
    for key, row in list(store.rows.items()):
        value = measured.get(str(row["scenario"]), "")
        if str(row.get("agreement") or "") != value:
            store.rows[key] = {**row, "agreement": value}
            done += 1
    return done


def _record_ranks(store: ResultsStore) -> int:
    """The ranks of rows stored without them (a name still not listed keeps -1, unrewritten)."""
    done = 0
    for key, row in list(store.rows.items()):
        if int(row.get("scenario_rank", -1)) >= 0 and int(row.get("engine_rank", -1)) >= 0:
            continue
        found = ranks(str(row["scenario"]), str(row["engine"]))
        if any(int(row.get(k, -1)) != v for k, v in found.items()):
            store.rows[key] = {**row, **found}
            done += 1
    return done
