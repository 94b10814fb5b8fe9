"""The constraint residual of any trajectory, the measure of how well an engine closes the loops."""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from types import ModuleType

import numpy as np

from reference_solver.compiled import pays, residual_kernels
from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.program import Program, compile_dense
from reference_solver.layout import Layout
from reference_solver.system import ConstraintSystem, equation_for
from scenarios.kept import kept
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory


def constraint_residual(
    scenario: Scenario, trajectory: Trajectory, compiled: bool | None = True
) -> np.ndarray:
    """Per time point, the largest |C| over the scenario's constraints (drivers included) at the
    trajectory's positions, lengths in units of the characteristic length.

    Cam contacts count only when the trajectory carries their parameter as the extra `<name>.phi`.
    The trajectory must have positions of every body of the scenario. Where the scenario compiles
    (cams too), the compiled rows evaluate C over the whole trajectory in one call, far
    cheaper than the plain rows; `plain_constraint_residual` is the same
    measure on the plain rows, which checks it. A time where a counted constraint reads NaN (a NaN
    coordinate) has a NaN residual on both. `compiled` False takes the plain rows; None takes the
    compiled ones where they pay (reference_solver.compiled.pays).
    """
    _check(scenario, trajectory)
    points = len(trajectory.times)
    found = _compiled(scenario) if pays("residuals", 3 * len(scenario.bodies), points, compiled) else None
    if found is None:
        return _plain_residual(scenario, trajectory)
    layout = found.layout
    known = _known_contacts(layout, trajectory)
    qs = _coordinates(layout, trajectory, known)
    counted = np.flatnonzero([contact is None or contact in known for contact in found.row_contacts])
    times = np.asarray(trajectory.times, dtype=float)
    measure = found.kernels.trajectory_residuals
    return measure(found.program, qs, times, found.row_scales, counted)  # type: ignore[no-any-return]


@dataclass(frozen=True)
class _Compiled:
    """A scenario's row instructions with what the residual reads beside them: the row scales and,
    per row, the cam contact it belongs to (None for every other constraint); `kernels` is
    reference_solver.compiled.residuals."""

    kernels: ModuleType
    program: Program
    layout: Layout
    row_scales: np.ndarray
    row_contacts: tuple[str | None, ...]


@kept(maxsize=8)
def _compiled(scenario: Scenario) -> _Compiled | None:
    """The scenario's compiled rows, None where they cannot be had (the plain rows then run); kept
    for the last few scenarios (a harness measures every run of a scenario's group against them:
    built once, not once a run)."""
    module, problem = residual_kernels()
    if module is None:
        warnings.warn(f"constraint residual: the plain rows run, {problem}", RuntimeWarning, stacklevel=4)
        return None
    system = ConstraintSystem(scenario)
    try:
        program = compile_dense(system)
    except NotCompiled:
        return None
    constraints = scenario.joints + scenario.drivers  # the system's equations, in order
    row_contacts = tuple(
        c.name if c in scenario.cams else None
        for c, eq in zip(constraints, system.equations, strict=True)
        for _ in range(eq.size)
    )
    return _Compiled(module, program, system.layout, np.asarray(system.row_scales, dtype=float), row_contacts)


def _known_contacts(layout: Layout, trajectory: Trajectory) -> set[str]:
    """The cam contacts whose parameter the trajectory carries (`<name>.phi`)."""
    return {c for c in layout.contacts if f"{c}.phi" in trajectory.extras}


def _coordinates(layout: Layout, trajectory: Trajectory, known: set[str]) -> np.ndarray:
    """q at every time point: the bodies' poses in the layout's order, then each `known` contact's
    parameter (0 for the others, whose rows do not count)."""
    assert trajectory.position is not None
    order = [trajectory.bodies.index(b) for b in layout.bodies]
    qs = np.zeros((len(trajectory.times), layout.size))
    qs[:, : 3 * len(order)] = trajectory.position[:, order, :].reshape(len(trajectory.times), -1)
    for c in known:
        qs[:, layout.phi_column(c)] = trajectory.extras[f"{c}.phi"]
    return qs


def _check(scenario: Scenario, trajectory: Trajectory) -> None:
    if trajectory.position is None:
        raise ValueError("the trajectory has no positions")
    missing = [b for b in Layout.of(scenario).bodies if b not in trajectory.bodies]
    if missing:
        raise ValueError(f"the trajectory lacks bodies {', '.join(missing)}")


def plain_constraint_residual(scenario: Scenario, trajectory: Trajectory) -> np.ndarray:
    """`constraint_residual` on the plain constraint rows."""
    _check(scenario, trajectory)
    return _plain_residual(scenario, trajectory)


def _plain_residual(scenario: Scenario, trajectory: Trajectory) -> np.ndarray:
    assert trajectory.position is not None
    layout = Layout.of(scenario)
    known_phi = _known_contacts(layout, trajectory)
    constraints = [
        c for c in scenario.joints + scenario.drivers if c not in scenario.cams or c.name in known_phi
    ]
    equations = [equation_for(c, layout) for c in constraints]
    scales = [np.array([layout.length_scale**p for p in eq.powers]) for eq in equations]
    order = [trajectory.bodies.index(b) for b in layout.bodies]
    q = np.zeros(layout.size)
    zero = np.zeros(layout.size)
    out = np.zeros(len(trajectory.times))
    for k, t in enumerate(trajectory.times):
        q[: 3 * len(order)] = trajectory.position[k, order, :].ravel()
        for c in known_phi:
            q[layout.phi_column(c)] = trajectory.extras[f"{c}.phi"][k]
        worst = 0.0
        for eq, scale in zip(equations, scales, strict=True):
            values = np.array([row.value for row in eq.constraint_rows(q, zero, float(t))]) / scale
            worst = float(np.max(np.abs(values), initial=worst))  # NaN stays NaN
        out[k] = worst
    return out
