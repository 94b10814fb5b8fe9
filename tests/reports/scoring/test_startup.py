"""The start-up figure (reports.scoring.startup) on made-up errors added to a closed form: a
decaying transient gives its excess and its time, a steady error gives neither, and one rule reads
every level."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from reports.scoring.startup import SETTLED, startup
from scenarios import build
from scenarios.closed_form import exact
from scenarios.scenario import characteristic_rate
from scenarios.trajectory import Trajectory


def _with_error(level: str, relative: np.ndarray):
    scenario = dataclasses.replace(build("four_bar"), steps=100)
    times = np.asarray(scenario.times())
    truth = exact(scenario, times)
    scale = (
        scenario.characteristic_length
        * characteristic_rate(scenario) ** {"velocity": 1, "acceleration": 2}[level]
    )
    values = np.array(truth.level(level), copy=True)
    values[:, 0, 0] += relative * scale
    result = dataclasses.replace(truth, **{level: values})
    return scenario, result, truth


def test_a_decaying_transient_gives_its_excess_and_its_time() -> None:
    k = np.arange(101)
    error = 1e-6 + 1e-2 * 0.8**k  # settles to 1e-6; above 2e-6 until 0.8^k <= 1e-4
    scenario, result, truth = _with_error("acceleration", error)
    found = startup(scenario, result, truth, ("position", "velocity", "acceleration"))
    steady = float(np.max(error[50:]))
    assert math.isclose(found["startup_excess"], float(np.max(error[:50])) / steady, rel_tol=1e-6)
    last = int(np.flatnonzero(error[:50] > SETTLED * steady)[-1])
    assert math.isclose(found["startup_time"], float(result.times[last] - result.times[0]), rel_tol=1e-12)
    assert 40 <= last <= 42  # 0.8^k 1e-2 crosses 1e-6 near k = 41


def test_a_steady_error_has_no_transient() -> None:
    scenario, result, truth = _with_error("velocity", np.full(101, 1e-6))
    found = startup(scenario, result, truth, ("velocity",))
    assert math.isclose(found["startup_excess"], 1.0, rel_tol=1e-6) and found["startup_time"] == 0.0


def _first_three(run: Trajectory) -> Trajectory:
    """`run` cut to its first three output times."""
    levels = ("times", "position", "velocity", "acceleration")
    return dataclasses.replace(run, **{level: getattr(run, level)[:3] for level in levels})


def test_too_short_a_grid_gives_no_figure() -> None:
    scenario, result, truth = _with_error("velocity", np.full(101, 1e-6))
    short, truth3 = (_first_three(r) for r in (result, truth))
    found = startup(scenario, short, truth3, ("velocity",))
    assert math.isnan(found["startup_excess"]) and math.isnan(found["startup_time"])
