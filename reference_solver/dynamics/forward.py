"""Forward dynamics to truth quality: coordinate partitioning integrated by scipy's DOP853 (or Radau
for stiff scenes) at a tight tolerance, restarted with a fresh partition when the dependent block
degrades. Positions satisfy the constraints to round-off at every output point; accuracy is the
integrator's tolerance. Alongside the motion it integrates the work of applied loads, dampers and
drivers, so the energy balance T + V - (T0 + V0) - W_applied - W_drivers + D_dampers = 0 is checked
at every output point.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import DOP853, OdeSolver, Radau, solve_ivp

from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p_grid import integrate
from reference_solver.dynamics.augmented import accelerations, constraint_outputs
from reference_solver.dynamics.compiled_rates import partitioned_ode
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.methods import ALI3P, ALI3P_STEP, METHODS
from reference_solver.dynamics.partition import Partitioned, State, choose_independent
from reference_solver.dynamics.partition_passage import is_passage, singular_passage
from reference_solver.errors import AssemblyError, ConvergenceError, SolverError
from reference_solver.layout import Layout
from reference_solver.solution import Analysis
from reference_solver.system import ConstraintSystem
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

REPARTITION = 0.1
"""Repartition when the dependent block's reciprocal condition number falls below this fraction of
its value when the partition was chosen."""


@dataclass(frozen=True)
class DynamicAnalysis:
    """The motion on the grid (as a kinematic Analysis: q, q', q'' and each point's constraint
    residual), the multipliers, and the extras (reactions, driver forces, energy, angles)."""

    motion: Analysis
    lam: np.ndarray
    extras: dict[str, np.ndarray] = field(default_factory=dict)
    evaluations: int = 0
    partitions: int = 1

    @property
    def layout(self) -> Layout:
        return self.motion.layout

    @property
    def times(self) -> np.ndarray:
        return self.motion.times

    @property
    def q(self) -> np.ndarray:
        return self.motion.q

    @property
    def qd(self) -> np.ndarray:
        return self.motion.qd

    @property
    def qdd(self) -> np.ndarray:
        return self.motion.qdd

    def trajectory(self, bodies: Sequence[str] | None = None) -> Trajectory:
        """The canonical trajectory of `bodies` (default all), with every extra as a column."""
        trajectory = self.motion.trajectory(bodies)
        trajectory.extras.update({k: v.copy() for k, v in self.extras.items()})
        return trajectory


def assemble_free(system: ConstraintSystem, q: np.ndarray, t: float) -> np.ndarray:
    """The configuration satisfying C(q, t) = 0 nearest the guess: minimum-norm Newton steps (scaled
    units) on the under-determined system."""
    q = q.copy()
    rows, cols = system.row_scales, system.column_scales
    for _ in range(50):
        c, jac, _ = system.evaluate(q, t)
        step = np.linalg.lstsq(system.scaled_jacobian(jac), -c / rows, rcond=None)[0]
        q += step * cols
        if np.max(np.abs(step), initial=0.0) < 1e-15:
            break
    residual = float(np.max(np.abs(system.residual(q, t) / rows), initial=0.0))
    if not residual < 1e-12:
        raise AssemblyError(
            f"{system.scenario.name}: the mechanism cannot assemble at t={t:.6g}: the constraints miss "
            f"by {residual:.3g} (relative to the characteristic length)",
            time=t,
            q=q,
        )
    return q


def initial_state(system: ConstraintSystem, mass: np.ndarray, loads: Loads, t: float) -> State:
    """Assembled positions and the rates nearest the bodies' given rates (kinetic-energy norm)."""
    scenario = system.scenario
    layout = system.layout
    q = assemble_free(system, layout.initial_guess(scenario), t)
    guess = np.concatenate([b.rate for b in scenario.bodies]).astype(float)
    jac = system.jacobian(q, t)
    n, m = layout.size, system.size
    kkt = np.block([[np.diag(mass), jac.T], [jac, np.zeros((m, m))]])
    qd = np.linalg.solve(kkt, np.concatenate([mass * guess, -system.c_t(t)]))[:n]
    load = loads(q, qd, t)
    qdd, lam = accelerations(jac, mass, load.generalized, system.q_d(q, qd, t))
    return State(t, q, qd, qdd, lam, jac, load)


def simulate(
    scenario: Scenario,
    times: Sequence[float] | np.ndarray | None = None,
    rtol: float = 1e-12,
    method: str = "DOP853",
    compiled: bool = False,
    step: float | None = None,
) -> DynamicAnalysis:
    """Forward dynamics of `scenario` on `times` (default: the scenario's grid, starting at t0), by
    coordinate partitioning integrated by `method` (one of METHODS) at `rtol`, or by ALI3-P
    (`method="ali3p"`, ali3p.py) at the fixed `step` (default ALI3P_STEP, cut to divide each output
    interval; `rtol` is not used there). `compiled` evaluates the constraints on the compiled path
    (compiled_system) and, for the partitioned method, the whole right-hand side in one compiled
    call (compiled_rates), equal to the plain one to 1e-12: the native engine asks for it by
    default, the dynamics suite's truth except through a singular passage, where round-off picks
    the motion (n_four_bar at rtol 1e-12, Newton started from each accepted step: energy held to
    7e-9 of the largest kinetic energy on the compiled right-hand side, 1.4e-9 on the plain path,
    the two 2e-8 of the length apart); ALI3-P passes it on either."""
    if method not in (*METHODS, ALI3P):
        raise SolverError(f"unknown integrator '{method}' (known: {', '.join((*METHODS, ALI3P))})")
    if step is not None and not (np.isfinite(step) and step > 0):
        raise SolverError(f"ALI3-P's step must be a positive number of seconds, not {step}")
    grid = np.asarray(scenario.times() if times is None else times, dtype=float)
    system = constraint_system(scenario, compiled)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    state = initial_state(system, mass, loads, float(grid[0]))
    if system.unknowns - np.linalg.matrix_rank(system.scaled_jacobian(state.jac)) == 0:
        raise SolverError(f"{scenario.name}: no degree of freedom is left to forward dynamics")
    kinetic0 = 0.5 * float(state.qd @ (mass * state.qd))
    energy0 = kinetic0 + state.loads.potential
    length = system.layout.length_scale
    span = float(grid[-1] - grid[0]) or 1.0
    energy_scale = max(abs(kinetic0) + abs(state.loads.potential), float(mass.sum()) * length**2 / span**2)

    if method == ALI3P:
        stepped, ali3p_works, steps = integrate(system, mass, loads, state, grid, step or ALI3P_STEP)
        return _result(system, mass, grid, stepped, ali3p_works, energy0, steps, 0)
    scales = (rtol, span, energy_scale)
    states, works, evaluations, partitions = _partitioned(system, mass, loads, state, grid, method, scales)
    return _result(system, mass, grid, states, np.array(works), energy0, evaluations, partitions)


def _partitioned(
    system: ConstraintSystem,
    mass: np.ndarray,
    loads: Loads,
    state: State,
    grid: np.ndarray,
    method: str,
    scales: tuple[float, float, float],
) -> tuple[list[State], list[np.ndarray], int, int]:
    """The partitioned method over `grid` from `state`: integrated by `method` at the tolerance of
    `scales` (rtol, the grid's span, the energy scale), partitioned anew wherever the chosen
    independent coordinates' conditioning degrades REPARTITION times. Next to a singular passage
    (partition_passage), where no partition helps, a failure says which passage it could not cross.
    Returns the states and work at the grid times, the right-hand sides evaluated and the
    partitions made."""
    rtol, span, energy_scale = scales
    states: list[State] = [state]
    works: list[np.ndarray] = [np.zeros(3)]
    evaluations, partitions, work = 0, 0, np.zeros(3)
    t, k = float(grid[0]), 1
    name = system.scenario.name
    before = 0.0
    passage: tuple[float, np.ndarray] | None = None  # a passage approached: the last repartition, C_q there
    while k < len(grid):
        independent = choose_independent(system, state.jac)
        ode = partitioned_ode(system, mass, loads, state.q, independent)
        partitions += 1
        chosen = ode.conditioning(state.jac)
        passage = (t, state.jac) if is_passage(chosen, before) else None
        before = chosen
        cols = system.column_scales[independent]
        atol = np.concatenate([rtol * cols, rtol * cols / span, rtol * energy_scale * np.ones(3)])

        def degraded(t: float, y: np.ndarray, ode: Partitioned = ode, chosen: float = chosen) -> float:
            return ode.conditioning(ode.positions(t, y[: ode.size])[1]) - REPARTITION * chosen

        degraded.terminal = True  # type: ignore[attr-defined]
        try:
            sol = solve_ivp(
                ode.rates,
                (t, float(grid[-1])),
                ode.pack(state, work),
                method=anchored(method, ode),
                rtol=rtol,
                atol=atol,
                events=degraded,
                dense_output=True,
            )
            evaluations += ode.evaluations
            if sol.status == -1:
                if passage is not None:
                    raise singular_passage(system, float(sol.t[-1]), passage)
                raise SolverError(f"{name}: the integrator failed after t={t:.6g}: {sol.message}")
            end = float(sol.t_events[0][0]) if sol.status == 1 else float(grid[-1])
            ode.restart(state.q)
            outputs = grid[k:][grid[k:] <= end]
            for time, y, output in _walk(sol, outputs):
                if output:
                    states.append(ode.state(time, y))
                    works.append(y[2 * ode.size :].copy())
                ode.anchor(time, y)
            k += len(outputs)
            if sol.status == 1:
                t, y = end, sol.y_events[0][0]
                state, work = ode.state(t, y), y[2 * ode.size :].copy()
        except (ConvergenceError, np.linalg.LinAlgError) as error:
            if passage is not None:
                raise singular_passage(system, getattr(error, "time", None) or t, passage) from error
            if isinstance(error, ConvergenceError):
                raise
            raise SolverError(f"{name}: singular augmented matrix after t={t:.6g}: {error}") from error
    return states, works, evaluations, partitions


def anchored(method: str, ode: Partitioned) -> type[OdeSolver]:
    """scipy's `method` with Newton's start (Partitioned.anchor) moved to each step it accepts, so
    that a trial stage it rejects leaves nothing behind (see partition.py)."""
    base = {"DOP853": DOP853, "Radau": Radau}[method]

    class Anchored(base):  # type: ignore[misc, valid-type]
        def __init__(self, *args: object, **options: object) -> None:
            super().__init__(*args, **options)
            ode.anchor(self.t, self.y)

        def _step_impl(self) -> tuple[bool, str | None]:
            accepted, message = super()._step_impl()
            if accepted:
                ode.anchor(self.t, self.y)
            return accepted, message

    return Anchored


def _walk(sol: object, outputs: np.ndarray) -> Iterator[tuple[float, np.ndarray, bool]]:
    """The dense solution at each output time (flagged True), with the integrator's own steps in
    between (flagged False): walking through them keeps Newton on the dependent coordinates near.
    Every step before the last output is walked (a step past one output comes before the next)."""
    step_times, step_states = sol.t, sol.y.T  # type: ignore[attr-defined]
    k = 0
    for time in outputs:
        while k < len(step_times) and step_times[k] < time:
            yield float(step_times[k]), step_states[k], False
            k += 1
        yield float(time), sol.sol(time), True  # type: ignore[attr-defined]


def angle_columns(scenario: Scenario, layout: Layout, q: np.ndarray) -> dict[str, np.ndarray]:
    """The scenario's extra angle columns from the absolute angles."""

    def angle(body: str) -> np.ndarray:
        col = layout.body_column(body)
        return np.zeros(len(q)) if col is None else q[:, col + 2]

    return {a.name: angle(a.body) - angle(a.relative_to) for a in scenario.angle_outputs}


def _result(
    system: ConstraintSystem,
    mass: np.ndarray,
    grid: np.ndarray,
    states: list[State],
    works: np.ndarray,
    energy0: float,
    evaluations: int,
    partitions: int,
) -> DynamicAnalysis:
    q = np.array([s.q for s in states])
    qd = np.array([s.qd for s in states])
    kinetic = 0.5 * np.einsum("ij,j,ij->i", qd, mass, qd)
    potential = np.array([s.loads.potential for s in states])
    outputs = [constraint_outputs(system, s.jac, s.lam) for s in states]
    extras = {key: np.array([o[key] for o in outputs]) for key in outputs[0]}
    extras.update(
        {
            "energy.kinetic": kinetic,
            "energy.potential": potential,
            "energy.applied_work": works[:, 0],
            "energy.dissipated": works[:, 1],
            "energy.driver_work": works[:, 2],
            "energy.balance": kinetic + potential - energy0 - works[:, 0] - works[:, 2] + works[:, 1],
        }
    )
    extras.update(angle_columns(system.scenario, system.layout, q))
    residual = np.array(
        [np.max(np.abs(system.residual(s.q, s.t) / system.row_scales), initial=0.0) for s in states]
    )
    motion = Analysis(
        system.layout,
        grid.copy(),
        q,
        qd,
        np.array([s.qdd for s in states]),
        np.zeros(len(states), dtype=int),
        residual,
        np.full(len(states), np.nan),
    )
    return DynamicAnalysis(motion, np.array([s.lam for s in states]), extras, evaluations, partitions)
