"""The work done on a mechanism since the first grid time, from a run's own trajectory.

Power enters through the applied loads (a torque times its body's rate relative to its reaction, a
force times its point's velocity), leaves through the dampers (c times the squared stretch or turn
rate), and enters through the drivers (the driving force the run reports, `<driver>.force`, times its
coordinate's rate). It is integrated over the grid by the trapezoidal rule with the cubic Hermite
end correction + h^2/12 (P0' - P1'): fourth order where every term's rate is known from the run's
accelerations and the load laws (Andrews' motor), third order where the rate is taken from the
power's own samples by second-order differences (a driving force's rate is not reported). With
E = T + V (scoring.energy_drift), E(t) - E(t0) = W(t) for an exact run: scoring.self_check judges a
run by how far it is from that.
"""

from __future__ import annotations

import numpy as np

from reports.scoring.forces import DRIVER_SUFFIX
from scenarios.bodies import GROUND, Point
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory


class _Motion:
    """Body and point kinematics of one trajectory, as (N, ...) arrays."""

    def __init__(self, trajectory: Trajectory) -> None:
        self.trajectory = trajectory
        self.count = len(trajectory.times)

    def _body(self, level: np.ndarray | None, body: str) -> np.ndarray:
        if body == GROUND or level is None:
            return np.zeros((self.count, 3))
        return level[:, self.trajectory.bodies.index(body), :]

    def rate(self, body: str) -> np.ndarray:
        return self._body(self.trajectory.velocity, body)[:, 2]

    def angular_acceleration(self, body: str) -> np.ndarray:
        return self._body(self.trajectory.acceleration, body)[:, 2]

    def _arm(self, point: Point) -> np.ndarray:
        theta = self._body(self.trajectory.position, point.body)[:, 2]
        c, s = np.cos(theta), np.sin(theta)
        x, y = point.local
        return np.stack([c * x - s * y, s * x + c * y], axis=-1)

    def velocity(self, point: Point) -> np.ndarray:
        v, arm = self._body(self.trajectory.velocity, point.body), self._arm(point)
        return v[:, :2] + v[:, 2:3] * np.stack([-arm[:, 1], arm[:, 0]], axis=-1)

    def acceleration(self, point: Point) -> np.ndarray:
        a, arm = self._body(self.trajectory.acceleration, point.body), self._arm(point)
        omega = self._body(self.trajectory.velocity, point.body)[:, 2:3]
        return a[:, :2] + a[:, 2:3] * np.stack([-arm[:, 1], arm[:, 0]], axis=-1) - omega**2 * arm

    def position(self, point: Point) -> np.ndarray:
        if point.body == GROUND:
            return np.broadcast_to(np.asarray(point.local, dtype=float), (self.count, 2))
        return self._body(self.trajectory.position, point.body)[:, :2] + self._arm(point)


def power(scenario: Scenario, trajectory: Trajectory) -> tuple[np.ndarray, np.ndarray | None] | None:
    """The power put into the mechanism at each grid time and its rate (None where a term's rate is
    unknown); None where a driver's force is not in the trajectory."""
    m, times = _Motion(trajectory), np.asarray(trajectory.times, dtype=float)
    total, slope = np.zeros(m.count), np.zeros(m.count)
    exact = trajectory.acceleration is not None
    for force in scenario.forces:
        if isinstance(force, AppliedTorque):
            torque = np.array([force.torque.f(t) for t in times])
            turn = np.array([force.torque.df(t) for t in times])
            rate = m.rate(force.body) - m.rate(force.reaction)
            total += torque * rate
            slope += turn * rate + torque * (
                m.angular_acceleration(force.body) - m.angular_acceleration(force.reaction)
            )
        elif isinstance(force, AppliedForce):
            pull = np.array([[force.fx.f(t), force.fy.f(t)] for t in times])
            change = np.array([[force.fx.df(t), force.fy.df(t)] for t in times])
            velocity = m.velocity(force.point)
            total += np.sum(pull * velocity, axis=1)
            slope += np.sum(change * velocity + pull * m.acceleration(force.point), axis=1)
        elif isinstance(force, SpringDamper) and force.damping:
            gap = m.position(force.p_j) - m.position(force.p_i)
            unit = gap / np.hypot(gap[:, :1], gap[:, 1:])
            stretch = np.sum((m.velocity(force.p_j) - m.velocity(force.p_i)) * unit, axis=1)
            total -= force.damping * stretch**2
            exact = False
        elif isinstance(force, RotationalSpringDamper) and force.damping:
            turn_rate = m.rate(force.body_j) - m.rate(force.body_i)
            total -= force.damping * turn_rate**2
            slope -= (
                2.0
                * force.damping
                * turn_rate
                * (m.angular_acceleration(force.body_j) - m.angular_acceleration(force.body_i))
            )
    for driver in scenario.drivers:
        found = _driver_power(driver, trajectory, m)
        if found is None:
            return None
        total += found
        exact = False
    return total, slope if exact else None


def _driver_power(driver: object, trajectory: Trajectory, m: _Motion) -> np.ndarray | None:
    """A driver's reported force times its coordinate's rate; None if the force is not reported."""
    extras = trajectory.extras
    name = getattr(driver, "name", "")
    if isinstance(driver, AbsoluteDriver | RelativeRotationDriver):
        force = extras.get(f"{name}{DRIVER_SUFFIX}")
        if force is None:
            return None
        if isinstance(driver, RelativeRotationDriver):
            return force * (m.rate(driver.body_i) - m.rate(driver.body_j))
        velocity = m._body(trajectory.velocity, driver.body)
        return force * velocity[:, ("x", "y", "theta").index(driver.coordinate)]
    pair = [extras.get(f"{name}.{axis}{DRIVER_SUFFIX}") for axis in ("x", "y")]
    if pair[0] is None or pair[1] is None:
        return None
    if isinstance(driver, PointPathDriver):
        velocity = m.velocity(driver.point)
    elif isinstance(driver, RelativeDisplacementDriver):
        velocity = m.velocity(driver.p_i) - m.velocity(driver.p_j)
    else:
        return None
    return pair[0] * velocity[:, 0] + pair[1] * velocity[:, 1]


def work(scenario: Scenario, trajectory: Trajectory) -> np.ndarray | None:
    """The work done on the mechanism from the first grid time to each one; None where a driver's
    force is not reported."""
    found = power(scenario, trajectory)
    if found is None:
        return None
    total, slope = found
    times = np.asarray(trajectory.times, dtype=float)
    if slope is None and times.size >= 3:
        slope = np.gradient(total, times, edge_order=2)  # second-order slopes: third-order work
    h = np.diff(times)
    pieces = 0.5 * h * (total[:-1] + total[1:])
    if slope is not None:
        pieces += h**2 / 12.0 * (slope[:-1] - slope[1:])
    return np.concatenate([[0.0], np.cumsum(pieces)])
