"""What the dynamics section of a report shows, decided when the run is made and stored.

After a suite's runs, for every stored row that has none yet:
- a row at a stiffness-step map cell gets its verdict (reports.dynamics.stability), the cell's
  stiffness and step, and the verdict's definition as its detail;
- a dynamic scenario's default run (the trajectories the store keeps) gets its energy drift
  (reports.scoring.energy_drift) and its scaled constraint residual (the native constraint
  equations) at each time, as extras of its stored trajectory (reports.store.columns.DRIFT_SERIES).
The report draws these as stored and never evaluates a scenario (reports.render).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from reference_solver import constraint_residual
from reports.dynamics.cases import is_dynamic, map_cells
from reports.dynamics.stability import DRIFTED, verdict
from reports.scoring import drift_series
from reports.store import DRIFT_SERIES, TRUTH, ResultsStore, stored_scenario, stored_truths
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

DEFINITION = (
    f"stable: position error and energy drift at most {DRIFTED:g}; drifted: above; otherwise the "
    "engine's own outcome"
)
"""The map's verdicts, stored as each cell's detail (the report's caption)."""


def record(store: ResultsStore) -> int:
    """Record the map cells' verdicts and the dynamic default runs' drift series of `store` where
    they are missing (the caller saves); returns how many rows and trajectories were recorded."""
    return _record_cells(store) + _record_series(store)


def _record_cells(store: ResultsStore) -> int:
    cells = map_cells()
    done = 0
    for key, row in list(store.rows.items()):
        name = str(row["scenario"])
        if name not in cells or str(row.get("verdict") or ""):
            continue
        values = cells[name]
        store.rows[key] = {
            **row,
            "verdict": verdict(row),
            "verdict_detail": DEFINITION,
            "map_stiffness": values["stiffness"],
            "map_dt": values["dt"],
        }
        done += 1
    return done


def _record_series(store: ResultsStore) -> int:
    truths = stored_truths(store.trajectories)
    scenarios: dict[str, Scenario | None] = {}
    done = 0
    for key, run in list(store.trajectories.items()):
        name, engine, _ = key
        truth = truths.get(name)
        if engine == TRUTH or truth is None or not is_dynamic(name) or name in map_cells():
            continue
        if all(extra in run.extras for extra in DRIFT_SERIES.values()):
            continue
        if name not in scenarios:
            scenarios[name] = stored_scenario(name)
        scenario = scenarios[name]
        if scenario is None:
            continue
        store.trajectories[key] = dataclasses.replace(
            run, extras={**run.extras, **series(scenario, run, truth)}
        )
        done += 1
    return done


def series(scenario: Scenario, run: Trajectory, truth: Trajectory) -> dict[str, np.ndarray]:
    """The run's energy drift and constraint residual at each time, by their extras' names (left out
    where the run cannot give one: no velocities, a body missing)."""
    shown = run.select(truth.bodies)
    out = {}
    for label, measure in (("energy drift", drift_series), ("constraint residual", _residual)):
        try:
            out[DRIFT_SERIES[label]] = np.asarray(measure(scenario, shown, truth), dtype=float)
        except (ValueError, KeyError, IndexError):
            continue
    return out


def _residual(scenario: Scenario, run: Trajectory, truth: Trajectory) -> np.ndarray:
    """The run's scaled constraint residual at each time (the truth is not needed)."""
    return np.abs(constraint_residual(scenario, run))
