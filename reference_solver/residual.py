"""The constraint residual of any trajectory, the measure of how well an engine closes the loops."""

from __future__ import annotations

import numpy as np

from reference_solver.compiled_system import CompiledSystem, constraint_system
from reference_solver.kept import kept
from reference_solver.layout import Layout
from reference_solver.system import ConstraintSystem, equation_for
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory


def constraint_residual(scenario: Scenario, trajectory: Trajectory) -> np.ndarray:
    """Per time point, the largest |C| over the scenario's constraints (drivers included) at the
    trajectory's positions, lengths in units of the characteristic length.

    Cam contacts count only when the trajectory carries their parameter as the extra `<name>.phi`.
    The trajectory must have positions of every body of the scenario. Where the scenario compiles
    (no cams), the compiled rows evaluate C over the whole trajectory in one call (about 0.2 ms for
    201 points, where a call per point cost about 2 ms and the plain rows about 20 ms);
    `plain_constraint_residual` is the same measure on the plain rows, which checks it.
    """
    _check(scenario, trajectory)
    system = _system(scenario) if not scenario.cams else None
    if not isinstance(system, CompiledSystem):
        return _plain_residual(scenario, trajectory)
    layout = system.layout
    order = [trajectory.bodies.index(b) for b in layout.bodies]
    assert trajectory.position is not None
    qs = np.zeros((len(trajectory.times), layout.size))
    qs[:, : 3 * len(order)] = trajectory.position[:, order, :].reshape(len(trajectory.times), -1)
    rows = np.ascontiguousarray(system.row_scales, dtype=float)
    return system.kernels.residuals(qs, np.asarray(trajectory.times, dtype=float), rows)  # type: ignore[no-any-return]


@kept(maxsize=8)
def _system(scenario: Scenario) -> ConstraintSystem:
    """The scenario's constraint system, kept for the last few scenarios (a harness measures every
    run of a scenario's group against it: built once, not once a run)."""
    return constraint_system(scenario)


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
    known_phi = {c for c in layout.contacts if f"{c}.phi" in trajectory.extras}
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
            worst = max(worst, float(np.max(np.abs(values))))
        out[k] = worst
    return out
