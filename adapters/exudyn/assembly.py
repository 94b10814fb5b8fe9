"""A consistent start in Exudyn: its static solver's assembly, then velocity and acceleration solves
on Exudyn's own constraint Jacobian (ConstraintProbe), written into the system's initial state; and
how an Exudyn solve's failure becomes an EngineFailure (Singular when its linear solver failed)
carrying Exudyn's own message and the simulated time.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import exudyn as exu
import numpy as np

from adapters.base import EngineFailure, Singular
from adapters.exudyn.model import ExudynModel

INITIAL = exu.ConfigurationType.Initial
CURRENT = exu.ConfigurationType.Current


@dataclass
class States:
    """Coordinates, velocities and accelerations (n_times x n_ode2) at the grid times."""

    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    forces: dict[str, np.ndarray] = field(default_factory=dict)
    """Drivers' forces and joints' reactions where the integrator recorded them (force_sensors)."""


ASSEMBLY_TOLERANCE = 1e-14


class ConstraintProbe:
    """Exudyn's constraint Jacobian C_q and velocity-level constraints C_q v + C_t at any state,
    through the interface of its static solver."""

    def __init__(self, model: ExudynModel, settings: Any) -> None:
        self.mbs = model.mbs
        self.solver = _static_solver()
        self.solver.InitializeSolver(self.mbs, settings)
        self.n = self.solver.GetODE2size()
        # a joint with a row switched off (a prismatic joint free to turn) keeps it as lambda = 0:
        # no coordinate in it, a 1 on the multiplier's diagonal; only the other rows constrain
        full = self._full_jacobian()
        self.live = np.flatnonzero(np.diag(full[self.n :, self.n :]) == 0.0)
        if len(self.live) != self.n:
            raise EngineFailure(
                f"not kinematically driven in Exudyn: {self.n} coordinates, {len(self.live)} constraints"
            )

    def _set(self, q: np.ndarray, v: np.ndarray, t: float) -> None:
        data = self.mbs.systemData
        data.SetODE2Coordinates(q.tolist(), CURRENT)
        data.SetODE2Coordinates_t(v.tolist(), CURRENT)
        data.SetTime(t)

    def _full_jacobian(self) -> np.ndarray:
        self.solver.ComputeJacobianODE2RHS(
            self.mbs, scalarFactor_ODE2=-1.0, scalarFactor_ODE2_t=0.0
        )  # resets
        self.solver.ComputeJacobianAE(self.mbs, scalarFactor_ODE2=1.0, scalarFactor_ODE2_t=0.0)
        return np.array(self.solver.GetSystemJacobian())

    def jacobian(self, q: np.ndarray, t: float) -> np.ndarray:
        self._set(q, np.zeros_like(q), t)
        return self._full_jacobian()[self.n + self.live, : self.n]

    def residual(self, q: np.ndarray, t: float) -> np.ndarray:
        """C(q, t), the constraints at position level."""
        self._set(q, np.zeros_like(q), t)
        self.solver.ComputeAlgebraicEquations(self.mbs, velocityLevel=False)
        return np.array(self.solver.GetSystemResidual())[self.n + self.live]

    def rate_residual(self, q: np.ndarray, v: np.ndarray, t: float) -> np.ndarray:
        """C_q v + C_t, the constraints at velocity level."""
        self._set(q, v, t)
        self.solver.ComputeAlgebraicEquations(self.mbs, velocityLevel=True)
        return np.array(self.solver.GetSystemResidual())[self.n + self.live]

    def rates(
        self, q: np.ndarray, t: float, scale: np.ndarray, frequency: float
    ) -> tuple[np.ndarray, np.ndarray]:
        """Velocities from C_q v = -C_t and accelerations from C_q a = Q_d, Q_d being minus the
        derivative of C_q v + C_t along the motion at fixed v (fourth-order central differences
        over a thousandth of the time a coordinate takes to move its own scale, or of 1/frequency)."""
        jac = self.jacobian(q, t)
        v = _solve(jac, -self.rate_residual(q, np.zeros_like(q), t), t)
        h = 1e-3 / max(float(np.max(np.abs(v) / scale)), frequency)

        def along(s: float) -> np.ndarray:
            return self.rate_residual(q + s * h * v, v, t + s * h)

        derivative = (8.0 * (along(1) - along(-1)) - (along(2) - along(-2))) / (12.0 * h)
        return v, _solve(jac, -derivative, t)

    def close(self, settings: Any) -> None:
        self.solver.FinalizeSolver(self.mbs, settings)


def _static_solver() -> Any:
    """Exudyn's static solver interface, typed Any: Exudyn's stubs of its methods lack `self`."""
    return exu.MainSolverStatic()


def _solve(jac: np.ndarray, rhs: np.ndarray, t: float) -> np.ndarray:
    if not np.all(np.isfinite(jac)) or np.linalg.cond(jac) > 1e14:
        raise Singular("Exudyn's constraint Jacobian is singular", t)
    return np.linalg.solve(jac, rhs)


def coordinate_scales(model: ExudynModel) -> tuple[np.ndarray, float]:
    """Per ODE2 coordinate the characteristic length for x and y, 1 for angles and phi; and the
    scenario's characteristic frequency, 2 pi over its duration."""
    scale = np.ones(len(model.guess))
    for index in model.index.values():
        scale[index : index + 2] = model.scenario.characteristic_length
    return scale, 2.0 * math.pi / model.scenario.t_end


def assemble(model: ExudynModel, t0: float, settings: Any) -> States:
    """A consistent start found by Exudyn: its static solver from the guess at t0, then velocity
    and acceleration solves; written into the system's initial state."""
    if t0 < 0.0:
        raise EngineFailure(f"Exudyn's static solver cannot start at negative time {t0}", t0)
    data = model.mbs.systemData
    data.SetODE2Coordinates(model.guess.tolist(), INITIAL)
    data.SetODE2Coordinates_t(np.zeros_like(model.guess).tolist(), INITIAL)
    static = settings.staticSolver
    static.numberOfLoadSteps, static.loadStepStart, static.loadStepDuration = 1, t0, 1e-30
    tolerance = ASSEMBLY_TOLERANCE * max(1.0, float(np.max(np.abs(model.guess))))
    static.newton.relativeTolerance, static.newton.absoluteTolerance = tolerance, tolerance
    guarded(model, "staticSolver", lambda: model.mbs.SolveStatic(settings, updateInitialValues=True))
    q0 = np.array(data.GetODE2Coordinates(INITIAL))
    probe = ConstraintProbe(model, settings)
    # Exudyn's static solve ends at t0 + 1e-30 (a load step must last); one Newton step on its
    # equations lands the start exactly at t0
    q0 = q0 - _solve(probe.jacobian(q0, t0), probe.residual(q0, t0), t0)
    gap = float(np.max(np.abs(probe.residual(q0, t0)), initial=0.0))
    if not gap <= 1e-9 * max(1.0, model.scenario.characteristic_length):
        raise EngineFailure(
            f"Exudyn's static solver did not assemble the mechanism: constraint residual {gap:.3g}", t0
        )
    q0 = _nearest_turns(model, probe, q0, t0, gap + 1e-12)
    v0, a0 = probe.rates(q0, t0, *coordinate_scales(model))
    probe.close(settings)
    start = States(q0[None, :], v0[None, :], a0[None, :])
    write_initial(model, start)
    return start


def write_initial(model: ExudynModel, start: States) -> None:
    """`start` as the system's initial state."""
    data = model.mbs.systemData
    data.SetODE2Coordinates(start.q[0].tolist(), INITIAL)
    data.SetODE2Coordinates_t(start.v[0].tolist(), INITIAL)
    data.SetODE2Coordinates_tt(start.a[0].tolist(), INITIAL)


def _nearest_turns(
    model: ExudynModel, probe: ConstraintProbe, q: np.ndarray, t: float, gap: float
) -> np.ndarray:
    """Each angle (and cam parameter) that Newton threw whole turns from its guess, brought back
    where no constraint minds (drivers and gears do fix absolute angles): the same configuration,
    on the continuous angle the guess asks for."""
    for k in [i + 2 for i in model.index.values()] + list(model.phi_index.values()):
        turns = round((q[k] - model.guess[k]) / (2.0 * math.pi))
        if turns:
            trial = q.copy()
            trial[k] -= 2.0 * math.pi * turns
            if float(np.max(np.abs(probe.residual(trial, t)))) <= gap:
                q = trial
    return q


def guarded(model: ExudynModel, key: str, solve: Callable[[], Any]) -> None:
    """Run an Exudyn solve; its failure becomes an EngineFailure with Exudyn's message."""
    try:
        ok = solve()
    except exu.SolverError as error:
        raise _failure(model, key, str(error)) from error
    except RuntimeError as error:  # Exudyn raises plain RuntimeErrors from inside its solvers too
        raise _failure(model, key, f"{type(error).__name__}: {error}") from error
    if ok is False:
        raise _failure(model, key, "solver returned failure")


def _failure(model: ExudynModel, key: str, text: str) -> EngineFailure:
    t = float(model.mbs.systemData.GetTime())
    solver = model.mbs.sys.get(key)
    name = "SolveStatic" if key == "staticSolver" else "SolveDynamic"
    if solver is None:
        return EngineFailure(f"Exudyn {name}: {text}", t)
    conv = solver.conv
    reason = solver.GetErrorString() or text
    detail = f"Newton residual {conv.residual:.3g}"
    if conv.linearSolverFailed:
        detail += f"; the linear solver failed (singular Jacobian, row {conv.linearSolverCausingRow})"
    kind = Singular if conv.linearSolverFailed else EngineFailure
    return kind(f"Exudyn {name}: {reason} ({detail})", t)
