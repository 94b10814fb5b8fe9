"""The stress suite's and the swept points' verdicts, decided when the run is made and stored.

After a suite's runs, every stored row a stability map shows gets its verdict columns
(the verdict columns of reports.store.columns), judged by reports.stress.stability_map from what the
store holds (the row, the default runs' trajectories, the truth; the branch check solves on the
scenario's constraint equations):
- in the stress suite, every row of a stress case, with the case's description (its place, what it
  probes, its closed-form singular time, its nominal scenario) and, for a long-horizon case's
  default runs, the error and residual over its first and last revolution;
- in any suite, the default row of every swept point (the swept stability map).
A row that has a verdict keeps it: a verdict is decided once, when its row is made. The report
reads these columns and never judges (reports.render).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from reference_solver import constraint_residual
from reports.scoring import headline_series
from reports.store import ResultsStore, stored_scenario, stored_truths
from reports.stress.cases import CASES, StressCase
from reports.stress.stability_map import columns, judge
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

STRESS_SUITE = "stress"


def record(store: ResultsStore, suite: str) -> int:
    """Judge the rows of `store` that a stability map shows and that have no verdict yet, and store
    the verdicts in them (the caller saves); returns how many rows were judged."""
    truths = stored_truths(store.trajectories)
    scenarios: dict[str, Scenario | None] = {}
    judged = 0
    for key, row in list(store.rows.items()):
        name = str(row["scenario"])
        case = CASES.get(name) if suite == STRESS_SUITE else None
        swept = bool(str(row.get("sweep") or "")) and bool(row["is_default"])
        if str(row.get("verdict") or "") or (case is None and not swept):
            continue
        if name not in scenarios:
            scenarios[name] = stored_scenario(name)
        result = store.trajectories.get(key)
        updates = columns(judge(row, result, truths.get(name), scenarios[name]))
        if case is not None:
            updates |= _case_columns(case)
            if case.drift and result is not None and truths.get(name) is not None:
                updates |= _drift_columns(scenarios[name], result, truths[name])
        store.rows[key] = {**row, **updates}
        judged += 1
    return judged


def _case_columns(case: StressCase) -> dict[str, Any]:
    """What the stability map says of the case: its place, what it probes, its closed-form singular
    time, the nominal scenario it is a similarity of."""
    singular = case.singular_time()
    return {
        "case_rank": list(CASES).index(case.name),
        "case_probes": case.probes,
        "case_singular_time": math.nan if singular is None else singular,
        "case_nominal": "" if case.similar is None else case.similar.nominal,
    }


def _drift_columns(scenario: Scenario | None, run: Trajectory, truth: Trajectory) -> dict[str, float]:
    """A long-horizon run's headline error and constraint residual over its first and its last
    revolution, and the angle it has drifted by the end."""
    if scenario is None:
        return {}
    per_turn = round(scenario.steps / float(scenario.parameter("revolutions")))
    errors = headline_series(run, truth, scenario.characteristic_length)
    parts = {"first": slice(0, per_turn + 1), "last": slice(len(run.times) - per_turn - 1, None)}
    out: dict[str, float] = {}
    for turn, part in parts.items():
        out[f"error_{turn}_rev"] = float(np.nanmax(errors[part]))
        out[f"residual_{turn}_rev"] = float(np.max(constraint_residual(scenario, _cut(run, part))))
    out["angle_error_end"] = _final_angle_error(run, truth)
    return out


def _final_angle_error(run: Trajectory, truth: Trajectory) -> float:
    """The largest angle error over the bodies at the last time: the phase the run has drifted."""
    mine, ref = run.select(truth.bodies).position, truth.position
    return math.nan if mine is None or ref is None else float(np.max(np.abs(mine[-1, :, 2] - ref[-1, :, 2])))


def _cut(run: Trajectory, part: slice) -> Trajectory:
    levels = {lv: None if (a := run.level(lv)) is None else a[part] for lv in run.levels}
    extras = {k: v[part] for k, v in run.extras.items()}
    return Trajectory(run.times[part], run.bodies, extras=extras, **levels)  # type: ignore[arg-type]
