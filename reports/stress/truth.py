"""The stress suite's truth: the reference solver, made to say where it has no answer.

- A case that is an exact similarity of a nominal scenario (reports.stress.cases.Similar) takes the
  nominal truth, mapped: lengths scaled, time stretched. It is then independent of the scale and
  speed the native solver is tested at, so the native solver's own error there is measured too.
- A case may ask for a finer grid (`refine`): the truth is solved there and sampled on the
  scenario's grid, so that the truth follows the branch where the scenario's grid would let the
  solver's predictor jump.
- Where the reference solver stops (a singular configuration, no configuration beyond), the truth
  holds the solution up to that time and NaN after it: no truth exists there, and no error is
  measured there.
"""

from __future__ import annotations

import dataclasses

import numpy as np

import reference_solver
from reports.stress.cases import Similar, StressCase, case
from scenarios import build
from scenarios.identity import family_twin
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

TOLERANCE = 1e-12
ATTEMPTS = 3


def declared_case(scenario: Scenario) -> StressCase:
    """The stress case `scenario` is: its name's declaration when it is that built-in mechanism
    (by digest), a bare case otherwise (a file that takes a case's name is another mechanism, and
    never gets the truth of a nominal scenario it is not a similarity of)."""
    return case(scenario.name) if family_twin(scenario) is not None else StressCase(scenario.name, "")


def stress_truth(scenario: Scenario, times: np.ndarray) -> Trajectory:
    """The truth of `scenario` on `times` (the runner's truth hook for the stress suite)."""
    declared = declared_case(scenario)
    grid = np.asarray(times, dtype=float)
    if declared.similar is not None:
        return similar_truth(declared.similar, grid)
    return partial_truth(scenario, grid, declared.refine)


def stress_truth_name(scenario: Scenario) -> str:
    """What the stress truth of `scenario` is, for the rows measured against it."""
    declared = declared_case(scenario)
    native = f"native, tolerance {TOLERANCE:g}"
    if declared.similar is not None:
        return f"{native} on {declared.similar.nominal}, scaled"
    return native + (f", grid refined {declared.refine}x" if declared.refine > 1 else "")


def similar_truth(similar: Similar, times: np.ndarray) -> Trajectory:
    """The nominal scenario's truth at speed * t, lengths times `length`, rates scaled to match."""
    nominal = partial_truth(build(similar.nominal), similar.speed * times, 1)
    s, k = similar.length, similar.speed

    def scaled(values: np.ndarray | None, length: float, angle: float) -> np.ndarray | None:
        return None if values is None else values * np.array([length, length, angle])

    return dataclasses.replace(
        nominal,
        times=times.copy(),
        position=scaled(nominal.position, s, 1.0),
        velocity=scaled(nominal.velocity, s * k, k),
        acceleration=scaled(nominal.acceleration, s * k * k, k * k),
    )


def partial_truth(scenario: Scenario, times: np.ndarray, refine: int = 1) -> Trajectory:
    """The reference solution on `times`, solved on a grid `refine` times finer; NaN from where the
    solver stops. An empty prefix (no assembly) raises the solver's error."""
    fine = _refined(times, refine)
    end = fine.size
    for _ in range(ATTEMPTS):
        try:
            solved = reference_solver.solve(scenario, fine[:end], tolerance=TOLERANCE)
            break
        except reference_solver.SolverError as error:
            if error.time is None:
                raise
            end = int(np.searchsorted(fine, error.time, side="left"))
            if end == 0:
                raise
    else:
        raise RuntimeError(f"{scenario.name}: the reference solver kept failing before its last stop")
    return _pad(solved, times, refine)


def _refined(times: np.ndarray, refine: int) -> np.ndarray:
    if refine <= 1 or times.size < 2:
        return times
    steps = np.linspace(0.0, 1.0, refine + 1)[:-1]
    inner = (times[:-1, None] + np.diff(times)[:, None] * steps[None, :]).ravel()
    return np.append(inner, times[-1])


def _pad(solved: Trajectory, times: np.ndarray, refine: int) -> Trajectory:
    """Every `refine`-th point of `solved`, NaN for the grid times it did not reach."""
    count = times.size

    def sample(values: np.ndarray) -> np.ndarray:
        picked = values[::refine]
        out = np.full((count, *values.shape[1:]), np.nan)
        out[: len(picked)] = picked
        return out

    levels = {lv: None if (v := solved.level(lv)) is None else sample(v) for lv in solved.levels}
    extras = {name: sample(values) for name, values in solved.extras.items()}
    return Trajectory(times.copy(), solved.bodies, extras=extras, **levels)  # type: ignore[arg-type]
