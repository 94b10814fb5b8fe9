"""The stability map: for every stress case, engine and setting, what became of the run.

The verdict of a stored row, decided when the run is made (reports.stress.recording stores it in the
row's verdict columns; the report reads them) from what the store holds: the row, the default runs'
trajectories and the truth, with the scenario rebuilt from its name to read its constraint equations:
    ok                  a result on the truth's branch (its error may still be large)
    picked a branch     past the truth's end (a singular configuration) the engine went on, on a
                        closure of the mechanism: the same branch or the mirrored one (detail)
    wrong branch        the result sits on another closure than the truth (reports.stress.branch_check)
    drifted             the result has left the mechanism: farther than LOST (0.1 of the
                        characteristic length, or 0.1 rad) from the truth and from any closure
    diverged            the engine's status: unstable, blown up
    singular detected   the engine's status: it stopped at a singular configuration
    failed to converge  the engine stopped because its iteration (Newton) did not converge
    failed              any other failure (assembly, an exception)
    timeout             the run hit the time limit
    unsupported         the engine cannot represent the scenario (the reason is the detail)
`time` is when it happened (the engine's failure time, the first time on another branch or
beyond LOST), `error` the largest headline error where the truth exists, `residual` the worst
constraint residual of the run.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from typing import Any

import numpy as np

from reports.scoring import headline_series
from reports.store import LOST, Judgement
from reports.stress.branch_check import ON_CLOSURE, check_branch
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

NO_CONVERGENCE = re.compile(r"converge|newton", re.IGNORECASE)
FAILURES = {"diverged": "diverged", "singular": "singular detected", "timeout": "timeout"}


Row = Mapping[str, Any]
"""A stored row: the store's dict, or a table's row."""


def columns(judged: Judgement) -> dict[str, Any]:
    """The verdict as the row's verdict columns (verdict, verdict_time, verdict_error, verdict_detail)."""
    return {
        "verdict": judged.verdict,
        "verdict_time": judged.time,
        "verdict_error": judged.error,
        "verdict_detail": judged.detail,
    }


Outcome = tuple[str, float, float, str]
"""verdict, time, error, detail"""


def judge(
    row: Row, result: Trajectory | None, truth: Trajectory | None, scenario: Scenario | None
) -> Judgement:
    """The verdict of one row; the branch check needs the row's trajectory, the truth and the scenario."""
    name, time, error, detail = _outcome(row, result, truth, scenario)
    return Judgement(
        str(row["scenario"]),
        str(row["engine"]),
        str(row["setting"]),
        bool(row["is_default"]),
        name,
        time,
        error,
        float(row["constraint_residual"]),
        detail,
    )


def _outcome(
    row: Row, result: Trajectory | None, truth: Trajectory | None, scenario: Scenario | None
) -> Outcome:
    status, message = str(row["status"]), str(row["message"])
    failure_time, nan = float(row["failure_time"]), math.nan
    if status == "unsupported":
        return "unsupported", nan, nan, message
    if status in FAILURES:
        note = _false_alarm(truth, failure_time)
        return FAILURES[status], failure_time, nan, f"{note}; {message}" if note else message
    if status != "ok":
        return (
            ("failed to converge" if NO_CONVERGENCE.search(message) else "failed"),
            failure_time,
            nan,
            message,
        )
    if result is None or truth is None:
        error, residual = float(row["error"]), float(row["constraint_residual"])
        if math.isfinite(error) and error > LOST:
            name = "wrong branch" if residual <= ON_CLOSURE else "drifted"
            return name, nan, error, "judged from the error and the residual (no stored trajectory)"
        return "ok", nan, error, ""
    series = headline_series(result, truth, float(row["characteristic_length"]))
    error = float(np.nanmax(series)) if np.any(np.isfinite(series)) else nan
    if scenario is None:
        return "ok", nan, error, "the scenario is no longer in the catalogue: branch not checked"
    return _from_trajectory(scenario, result, truth, series, error)


def _from_trajectory(
    scenario: Scenario, result: Trajectory, truth: Trajectory, series: np.ndarray, error: float
) -> Outcome:
    check = check_branch(scenario, result, truth)
    other = check.first("other")
    if other is not None:
        closure = "the mirrored closure" if other.mirrored else "another closure"
        return "wrong branch", other.time, error, f"on {closure}, {other.separation:.2g} from the truth"
    end = _truth_end(truth)
    lost = np.flatnonzero(series > LOST)
    off = [p for p in check.points if p.kind == "off"]
    if lost.size or (off and off[0].time <= end):
        when = float(result.times[lost[0]]) if lost.size else off[0].time
        return "drifted", when, error, "the result lies on no closure of the mechanism"
    if off:
        return "drifted", off[0].time, error, f"left the mechanism after the truth's end at {end:.4g} s"
    beyond = [p for p in check.points if p.kind in ("kept", "switched")]
    if beyond:
        branch = "the mirrored branch" if any(p.kind == "switched" for p in beyond) else "the same branch"
        return (
            "picked a branch",
            beyond[0].time,
            error,
            f"went on past the truth's end ({end:.4g} s) on {branch}",
        )
    return "ok", math.nan, error, ""


def _truth_end(truth: Trajectory) -> float:
    """The last time the truth has a configuration."""
    valid = np.all(np.isfinite(truth.position), axis=(1, 2)) if truth.position is not None else []
    return float(truth.times[np.flatnonzero(valid)[-1]]) if np.any(valid) else math.nan


def _false_alarm(truth: Trajectory | None, time: float) -> str:
    """A note when the truth (possibly solved on a finer grid) goes on past a failure time."""
    if truth is None or not math.isfinite(time):
        return ""
    end = _truth_end(truth)
    if math.isfinite(end) and end > time:
        return f"the truth goes on regular past {time:.4g} s, to {end:.4g} s (a false alarm or a jump)"
    return ""
