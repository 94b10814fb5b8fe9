"""IFToMM A02's own criterion, judged against the chain's one-degree-of-freedom equation.

On the parallelogram branch every rocker turns with the crank and every coupler translates, so the
chain of N loops (2N + 1 uniform links of length l and mass m) moves as one pendulum in the crank's
angle theta:

    I theta'' = -c cos theta,   I = m l^2 ((N + 1) / 3 + N),   c = m g l ((N + 1) / 2 + N)

(each rocker a rod about its pivot, each coupler a point mass m moving with the rockers' tips). It
is integrated here by DOP853 at rtol 1e-13, independently of any engine's multibody formulation; it
also gives the passage times (theta a multiple of pi), where the chain's links line up.

The specification (lim.ii.udc.es/mbsbenchmark/dist/A02/A02_specification.xml) judges the position
and velocity of point B0, the crank's tip, x and y, at 400 output steps: 1e-1 is its low-precision
and 1e-3 its high-precision limit. `criterion` reports that error as the largest absolute
difference over the grid and the four components (m and m/s: links of 1 m), beside the largest
angle of a rocker to the crank (0 on the parallelogram branch).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenarios.kept import kept
from scenarios.scenario import Level, Scenario
from scenarios.trajectory import Trajectory

HIGH_PRECISION = 1e-3
"""The specification's high-precision limit on B0's position (m) and velocity (m/s)."""
LOW_PRECISION = 1e-1
"""Its low-precision limit."""
SPEC_OUTPUTS = 400
"""The specification's output steps."""
RTOL = 1e-13


@dataclass(frozen=True)
class Reduced:
    """The one-degree-of-freedom motion: the crank's angle and rate on a dense solution, the passage
    times, and the chain's constants."""

    solution: object
    passages: np.ndarray
    length: float

    def angle(self, times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """theta and theta' at `times`."""
        theta, rate = self.solution.sol(np.asarray(times, dtype=float))  # type: ignore[attr-defined]
        return theta, rate

    def b0(self, times: np.ndarray) -> np.ndarray:
        """B0's x, y, vx, vy at `times`, shape (len(times), 4)."""
        theta, rate = self.angle(times)
        c, s = np.cos(theta), np.sin(theta)
        return self.length * np.column_stack([c, s, -s * rate, c * rate])


@kept(maxsize=8)
def reduced(scenario: Scenario) -> Reduced:
    """The one-degree-of-freedom solution of an n_four_bar scenario over its horizon."""
    from scipy.integrate import solve_ivp  # on first use: scipy's integrators are slow to import

    crank = scenario.body("crank")
    p = dict(scenario.parameters)
    loops, length, mass = int(p["loops"]), crank.length, crank.mass
    g = -scenario.gravity[1]
    inertia = mass * length**2 * ((loops + 1) / 3 + loops)
    weight = mass * g * length * ((loops + 1) / 2 + loops)
    start = float(p["theta0"])
    rate = crank.rate[2]
    solution = solve_ivp(
        lambda t, y: [y[1], -weight / inertia * math.cos(y[0])],
        (0.0, scenario.t_end),
        [start, rate],
        method="DOP853",
        rtol=RTOL,
        atol=RTOL,
        events=lambda t, y: math.sin(y[0]),
        dense_output=True,
    )
    return Reduced(solution, np.asarray(solution.t_events[0], dtype=float), length)


def b0_of(trajectory: Trajectory, length: float) -> np.ndarray:
    """B0's x, y, vx, vy from a trajectory's crank (frame at its midpoint, x along it)."""
    k = trajectory.bodies.index("crank")
    pos, vel = _level(trajectory, "position")[:, k, :], _level(trajectory, "velocity")[:, k, :]
    c, s, half = np.cos(pos[:, 2]), np.sin(pos[:, 2]), 0.5 * length
    return np.column_stack(
        [
            pos[:, 0] + half * c,
            pos[:, 1] + half * s,
            vel[:, 0] - half * s * vel[:, 2],
            vel[:, 1] + half * c * vel[:, 2],
        ]
    )


def criterion(scenario: Scenario, trajectory: Trajectory) -> dict[str, float]:
    """A02's figures of `trajectory` (positions and velocities of the crank and the rockers) on its
    grid: `benchmark_error`, the largest |B0 - B0_reference| over x, y, vx, vy and the grid (m and
    m/s), against `benchmark_limit`, the specification's high-precision limit, and
    `invariant_error`, the largest angle of any rocker to the crank (rad). The energy is every
    dynamic row's own figure (reports.scoring.energy_drift)."""
    found = reduced(scenario)
    theta = _level(trajectory, "position")[:, :, 2]
    rockers = [k for k, b in enumerate(trajectory.bodies) if b.startswith("rocker")]
    crank = trajectory.bodies.index("crank") if "crank" in trajectory.bodies else -1
    if crank < 0 or len(rockers) != int(dict(scenario.parameters)["loops"]):
        raise ValueError("A02's criterion needs the crank and every rocker")
    b0 = b0_of(trajectory, found.length)
    return {
        "benchmark_error": float(np.max(np.abs(b0 - found.b0(trajectory.times)))),
        "benchmark_limit": HIGH_PRECISION,
        "invariant_error": float(np.max(np.abs(theta[:, rockers] - theta[:, [crank]]), initial=0.0)),
    }


def _level(trajectory: Trajectory, level: Level) -> np.ndarray:
    values = trajectory.level(level)
    if values is None:
        raise ValueError(f"A02's criterion needs the trajectory's {level}s")
    return values
