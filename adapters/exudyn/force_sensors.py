"""Driving forces and joint reactions recorded by Exudyn's own object sensors.

A driver built as one `ObjectConnectorCoordinate` (factor1 q[m1] - q[m0] - offset = 0 with the ground
as m0) reports its Lagrange multiplier as `Force`; a revolute `ObjectJointRevolute2D` reports the
force of its constraint in world axes; a prismatic `ObjectJointPrismatic2D` reports it as
`ForceLocal`, the force on its marker-0 body in that body's axes (turned into world axes by the
body's angle at each time). Each becomes the canonical column the native solver writes
(reference_solver.dynamics.augmented.constraint_outputs): the force a driver applies along its
coordinate, the force a joint applies to its first moving body.
The signs were measured against the native inverse dynamics (tests/adapters/exudyn/test_forces.py).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import SensorObject

from adapters.lattice import lattice_point
from scenarios.bodies import GROUND
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.joints import Prismatic, Revolute

DRIVER_SIGN = -1.0
"""Exudyn's coordinate multiplier is the force on the marker-1 coordinate with the opposite sign."""
FORCE_ITEMS = (
    AbsoluteDriver,
    RelativeRotationDriver,
    RelativeDisplacementDriver,
    PointPathDriver,
    Revolute,
    Prismatic,
)
"""The items whose force the native solver reports (a driving force, a joint's reaction)."""
JOINT_SIGN = 1.0
"""A 2D joint's force is the force on its marker-0 body."""


@dataclass(frozen=True)
class ForceSensor:
    """One sensor and the columns it fills: (column, component, sign) per column."""

    handle: Any
    columns: tuple[tuple[str, int, float], ...]
    frame: str = GROUND
    """The body in whose axes the sensor reports (its x, y components turned by the body's angle)."""


def add_force_sensors(mbs: Any, items: dict[str, tuple[object, list[int]]]) -> list[ForceSensor]:
    """A Force sensor on every driver and joint built as one Exudyn object that reports its force;
    `items` maps each scenario name to the item and the objects built for it. A driver or joint
    left without one is named in a warning (the row's) with why."""
    sensors = []
    unsensed: list[str] = []
    for name, (item, objects) in items.items():
        if len(objects) != 1:
            if isinstance(item, FORCE_ITEMS):
                unsensed.append(f"'{name}' (built as {len(objects)} Exudyn objects)")
            continue
        kind = mbs.GetObject(objects[0])["objectType"]
        output, frame = exu.OutputVariableType.Force, GROUND
        if isinstance(item, AbsoluteDriver) and kind == "ConnectorCoordinate":
            columns: tuple[tuple[str, int, float], ...] = ((f"{name}.force", 0, DRIVER_SIGN),)
        elif isinstance(item, Revolute | Prismatic) and kind in ("JointRevolute2D", "JointPrismatic2D"):
            sign = JOINT_SIGN if item.p_i.body != GROUND else -JOINT_SIGN
            columns = ((f"{name}.fx", 0, sign), (f"{name}.fy", 1, sign))
            if kind == "JointPrismatic2D":
                output, frame = exu.OutputVariableType.ForceLocal, item.p_i.body
        else:
            if isinstance(item, FORCE_ITEMS):
                unsensed.append(f"'{name}' (an Exudyn {kind}, whose sensor gives no force of ours)")
            continue
        handle = mbs.AddSensor(
            SensorObject(
                objectNumber=objects[0], storeInternal=True, writeToFile=False, outputVariableType=output
            )
        )
        sensors.append(ForceSensor(handle, columns, frame))
    if unsensed:
        warnings.warn(f"forces not given: {', '.join(unsensed)}", stacklevel=2)
    return sensors


def force_columns(
    mbs: Any,
    sensors: list[ForceSensor],
    times: np.ndarray,
    h: float,
    initial: list[np.ndarray] | None,
    angle: dict[str, np.ndarray],
) -> dict[str, np.ndarray]:
    """Each sensor's columns on the output grid: the value stored at each lattice point t0 + k h
    (adapters.lattice), `initial` at t0 where given (a march that starts at t0 stores none there),
    linear between two lattice points for an output time between them; in world axes, a body's
    axes turned by its `angle` on the grid."""
    t0 = float(times[0])
    out: dict[str, np.ndarray] = {}
    for number, sensor in enumerate(sensors):
        data = np.asarray(mbs.GetSensorStoredData(sensor.handle))
        k = np.rint((data[:, 0] - t0) / h).astype(int)
        lattice = {int(j): row for j, row in zip(k, data[:, 1:], strict=True)}  # the last stored wins
        if initial is not None:
            lattice[0] = initial[number]
        values = np.empty((len(times), data.shape[1] - 1))
        for i, t in enumerate(times):
            whole, rest = lattice_point(t0, float(t), h)
            values[i] = lattice[whole]
            if rest > 0.0:
                values[i] += (rest / h) * (lattice[whole + 1] - lattice[whole])
        if sensor.frame != GROUND:
            c, s = np.cos(angle[sensor.frame]), np.sin(angle[sensor.frame])
            values[:, 0], values[:, 1] = (
                c * values[:, 0] - s * values[:, 1],
                s * values[:, 0] + c * values[:, 1],
            )
        for column, component, sign in sensor.columns:
            out[column] = sign * values[:, component]
    return out
