"""On which assembly branch an engine's trajectory lies, against the reference truth.

A kinematically driven mechanism has, at each time, a few isolated closures: configurations that
satisfy every constraint and driver (the open and the crossed four-bar, the slider on either side of
the crank). An engine's configuration is projected onto the nearest closure by Newton-Raphson on the
reference solver's constraint equations, started from the engine's own configuration:
- it is near the truth's closure: its error is an error of accuracy (`same`);
- it sits on another closure, far from the truth: a wrong assembly branch (`other`; `mirrored` when
  the Jacobian's determinant has the other sign, the mirrored closure of a single loop);
- it is farther than LOST from every closure: it has left the mechanism (`off`).
Beyond the truth's end (past a singular configuration no closure is the truth), the closure the
engine sits on is compared with the truth's last one by the sign of the determinant: the same
branch (`kept`) or the mirrored one (`switched`).

Distances are in scaled units: lengths divided by the scenario's characteristic length, angles and
contact parameters in radians (differences wrapped to (-pi, pi]).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from reference_solver.factorization import factorize
from reference_solver.layout import Layout
from reference_solver.newton import NewtonSettings, newton
from reference_solver.system import ConstraintSystem
from reports.store import LOST  # farther than it from every closure: `off`
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

Kind = Literal["same", "other", "off", "kept", "switched"]

CANDIDATE = 1e-3
"""Times where the engine is closer than this to the truth are on its branch without a check."""
ON_CLOSURE = 1e-2
"""An engine within this of another closure (and nearer it than the truth) sits on that closure."""
DISTINCT = 1e-6
"""Two closures farther apart than this are different branches."""
PROJECTION = NewtonSettings(1e-10, 1e-10, max_iterations=50, damped=True)


@dataclass(frozen=True)
class PointCheck:
    """The verdict at one time: `distance` from the engine to the closure found (NaN if none),
    `separation` of that closure from the truth (NaN beyond the truth)."""

    time: float
    kind: Kind
    distance: float
    separation: float
    mirrored: bool


@dataclass(frozen=True)
class BranchCheck:
    """The checked times in order (times close to the truth are not listed: they are `same`)."""

    points: tuple[PointCheck, ...]

    def first(self, *kinds: Kind) -> PointCheck | None:
        return next((p for p in self.points if p.kind in kinds), None)

    def last(self) -> PointCheck | None:
        return self.points[-1] if self.points else None


class Configurations:
    """Configurations (the solver's vector q) of a trajectory, for one scenario's layout."""

    def __init__(self, scenario: Scenario, trajectory: Trajectory, phi_fallback: Trajectory | None = None):
        if trajectory.position is None:
            raise ValueError("the trajectory has no positions")
        self.layout = Layout.of(scenario)
        missing = [b for b in self.layout.bodies if b not in trajectory.bodies]
        if missing:
            raise ValueError(f"the trajectory lacks bodies {', '.join(missing)}")
        order = [trajectory.bodies.index(b) for b in self.layout.bodies]
        count = len(trajectory.times)
        self.q = np.zeros((count, self.layout.size))
        self.q[:, : 3 * len(order)] = trajectory.position[:, order, :].reshape(count, -1)
        guesses = {c.name: c.phi_guess for c in scenario.cams}
        for contact in self.layout.contacts:
            column = self.layout.phi_column(contact)
            self.q[:, column] = _phi(contact, trajectory, phi_fallback, guesses[contact], count)

    def distance(self, a: np.ndarray, b: np.ndarray) -> float:
        """max over coordinates of |a - b| in scaled units, angle differences wrapped."""
        diff = (a - b) / self.layout.column_scales()
        angles = np.ones(self.layout.size, dtype=bool)
        angles[: 3 * len(self.layout.bodies)] = False
        angles[2 : 3 * len(self.layout.bodies) : 3] = True
        diff[angles] = np.angle(np.exp(1j * diff[angles]))
        return float(np.max(np.abs(diff))) if diff.size else 0.0


def _phi(
    contact: str, trajectory: Trajectory, fallback: Trajectory | None, guess: float, count: int
) -> np.ndarray:
    """The contact parameter from the trajectory, else the fallback's (carried past its end), else
    the scenario's guess."""
    key = f"{contact}.phi"
    if key in trajectory.extras:
        return np.asarray(trajectory.extras[key], dtype=float)
    values = np.full(count, guess)
    if fallback is not None and key in fallback.extras:
        known = np.asarray(fallback.extras[key], dtype=float)
        last = guess
        for k in range(count):
            last = known[k] if k < known.size and math.isfinite(known[k]) else last
            values[k] = last
    return values


def scaled_errors(engine: Configurations, truth: Configurations) -> np.ndarray:
    """The engine's distance from the truth at each time (NaN where the truth has none)."""
    out = np.full(len(engine.q), np.nan)
    for k in range(len(out)):
        if np.all(np.isfinite(truth.q[k])):
            out[k] = engine.distance(engine.q[k], truth.q[k])
    return out


def check_branch(
    scenario: Scenario, result: Trajectory, truth: Trajectory, max_points: int = 60
) -> BranchCheck:
    """Classify the engine's `result` against `truth` (same grid; the truth may be NaN past a
    singular configuration) at up to about 2 * max_points of the times where it strays from the
    truth: spread over them, then every one before the first departure found."""
    engine = Configurations(scenario, result, truth)
    reference = Configurations(scenario, truth)
    errors = scaled_errors(engine, reference)
    candidates = np.flatnonzero(~(errors <= CANDIDATE))  # far from the truth, or no truth there
    system = ConstraintSystem(scenario)
    valid = np.flatnonzero(np.all(np.isfinite(reference.q), axis=1))
    signs: dict[int, float] = {}

    def truth_sign(k: int) -> float:
        """det C_q's sign on the truth at its last valid time up to k."""
        before = valid[valid <= k]
        index = int(before[-1]) if before.size else int(valid[0]) if valid.size else -1
        if index < 0:
            return 0.0
        if index not in signs:
            jacobian = system.scaled_jacobian(system.jacobian(reference.q[index], float(truth.times[index])))
            signs[index] = factorize(jacobian).sign
        return signs[index]

    def check(k: int) -> PointCheck:
        truth_q = reference.q[k] if k in set_valid else None
        return _classify(system, engine, engine.q[k], truth_q, float(result.times[k]), truth_sign(k))

    set_valid = set(valid.tolist())
    points = {int(k): check(int(k)) for k in _spread(candidates, max_points)}
    first = next((k for k in sorted(points) if points[k].kind not in ("same", "kept")), None)
    if first is not None:
        previous = max((k for k in points if k < first), default=-1)
        gap = candidates[(candidates > previous) & (candidates < first)]
        points.update({int(k): check(int(k)) for k in _spread(gap, max_points)})
    return BranchCheck(tuple(points[k] for k in sorted(points)))


def _spread(indices: np.ndarray, count: int) -> np.ndarray:
    """At most `count` of `indices`, evenly spread, first and last included."""
    if indices.size <= count:
        return indices
    picks = np.unique(np.round(np.linspace(0, indices.size - 1, count)).astype(int))
    return indices[picks]


def _classify(
    system: ConstraintSystem,
    space: Configurations,
    q: np.ndarray,
    truth_q: np.ndarray | None,
    t: float,
    truth_sign: float,
) -> PointCheck:
    projected = newton(system, q, t, PROJECTION)
    error = math.nan if truth_q is None else space.distance(q, truth_q)
    if not projected.converged or projected.factors is None:
        return PointCheck(t, "same" if error <= LOST else "off", math.nan, math.nan, False)
    distance = space.distance(q, projected.q)
    mirrored = bool(projected.factors.sign * truth_sign < 0)
    if truth_q is None:
        kind: Kind = "off" if distance > LOST else "switched" if mirrored else "kept"
        return PointCheck(t, kind, distance, math.nan, mirrored)
    separation = space.distance(projected.q, truth_q)
    if separation > DISTINCT and distance <= min(ON_CLOSURE, 0.5 * separation):
        kind = "other"
    else:
        kind = "same" if error <= LOST else "off"
    return PointCheck(t, kind, distance, separation, mirrored)
