"""Consistent initial state from MuJoCo's own constraint rows.

MuJoCo does not assemble a closed loop: it starts wherever qpos is and lets the soft constraints
pull it shut, which is a transient, not the mechanism. So the start is solved on MuJoCo's rows:
Newton on the equality and contact residuals (efc_pos) with their Jacobian (efc_J) for the
positions, then the velocity rows J v = 0 for qvel, with the clocks held at their own values.
Tolerances and the contact margin are sized by the mechanism (adapters.mujoco.scale). A faceted cam
is many pairs on one follower geom (a group): within the margin several facets have rows, and only
the closest contact is the cam's (the distance to a convex polygon is the least of its facets'; a
disc's two contacts, at the ends of its capsule, are one row twice).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import mujoco
import numpy as np

from adapters.base import Singular
from adapters.mujoco.pairs import PairTable, closest_contacts, margins
from adapters.mujoco.scale import Scale, dof_sizes, row_tolerances

CAM_MARGIN = 1.0
"""Contact detection distance while assembling, in characteristic lengths, so that a separated cam
contact still has a row."""


@contextmanager
def _margin(m: mujoco.MjModel, scale: Scale, table: PairTable | None = None) -> Iterator[None]:
    """The cam contacts detected within CAM_MARGIN characteristic lengths meanwhile (`table`: as
    closest_contacts)."""
    with margins(m, PairTable.of(m) if table is None else table, CAM_MARGIN * scale.length):
        yield


def _rows(
    m: mujoco.MjModel, d: mujoco.MjData, table: PairTable | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Residuals and their Jacobian (rows x dofs) of the equalities and of each cam's closest
    contact (`table`: as closest_contacts). The position stage makes the rows (efc_pos, efc_J); the
    rest of a forward pass would solve them, hundreds of contact rows at the assembly's margin on a
    faceted cam (half its time there), and sets nothing a later step starts from (the solver's warm
    start is saved by a step only)."""
    mujoco.mj_fwdPosition(m, d)
    keep = d.efc_type == int(mujoco.mjtConstraint.mjCNSTR_EQUALITY)  # an int: numpy compares in C
    for i in closest_contacts(m, d, table).values():
        keep[d.contact[i].efc_address] = True
    jac = d.efc_J.reshape(d.nefc, m.nv)
    return d.efc_pos[keep].copy(), jac[keep].copy()


def assemble(
    m: mujoco.MjModel,
    d: mujoco.MjData,
    clocks: dict[int, tuple[float, float]],
    scale: Scale,
    iterations: int = 50,
    table: PairTable | None = None,
) -> None:
    """Solve d.qpos and d.qvel in place. `clocks` maps a clock's dof to its (qpos, qvel); MuJoCo's
    dofs and qpos coincide here (hinges and slides only). `table`: as closest_contacts."""
    sizes = dof_sizes(m, scale)
    table = PairTable.of(m) if table is None else table
    with _margin(m, scale, table):
        free = np.array([k for k in range(m.nv) if k not in clocks], dtype=int)
        for dof, (q, v) in clocks.items():
            d.qpos[dof], d.qvel[dof] = q, v
        excess = np.inf
        for _ in range(iterations):
            pos, jac = _rows(m, d, table)
            tolerance = row_tolerances(jac, sizes)
            excess = float(np.max(np.abs(pos) / tolerance, initial=0.0))
            if excess < 1.0:
                break
            step = np.linalg.lstsq(jac[:, free], -pos, rcond=None)[0]
            d.qpos[free] += step
        else:
            raise Singular(
                f"the mechanism does not assemble in MuJoCo (residual {excess:.3g} times its tolerance)", 0.0
            )
        _, jac = _rows(m, d, table)
        velocities(m, d, jac, {dof: v for dof, (_, v) in clocks.items()})
        velocity_residual = np.abs(jac @ d.qvel).max(initial=0.0)
        size = max(1.0, float(np.abs(d.qvel).max()))
        if velocity_residual > 1e-9 * size:
            raise Singular(f"the start velocity is not unique (residual {velocity_residual:.3g})", 0.0)
    mujoco.mj_forward(m, d)


def velocities(m: mujoco.MjModel, d: mujoco.MjData, jac: np.ndarray, clocks: dict[int, float]) -> None:
    """d.qvel with the clocks at the given rates and the other dofs on the velocity rows J v = 0."""
    free = np.array([k for k in range(m.nv) if k not in clocks], dtype=int)
    fixed = np.array(sorted(clocks), dtype=int)
    for dof, v in clocks.items():
        d.qvel[dof] = v
    rhs = -jac[:, fixed] @ d.qvel[fixed] if fixed.size else np.zeros(len(jac))
    d.qvel[free] = np.linalg.lstsq(jac[:, free], rhs, rcond=None)[0]


def clock_velocities(
    m: mujoco.MjModel, d: mujoco.MjData, clocks: list[int], scale: Scale
) -> list[np.ndarray]:
    """For each clock dof, qvel with that clock at unit rate and the others still (d unchanged)."""
    qvel = d.qvel.copy()
    with _margin(m, scale):
        _, jac = _rows(m, d)
    found = []
    for clock in clocks:
        velocities(m, d, jac, {c: float(c == clock) for c in clocks})
        found.append(d.qvel.copy())
    d.qvel[:] = qvel
    mujoco.mj_forward(m, d)
    return found


def contact_slopes(m: mujoco.MjModel, d: mujoco.MjData, scale: Scale) -> dict[int, np.ndarray]:
    """For each cam contact (pair group, by index), the gradient of its distance over the dofs."""
    with _margin(m, scale):
        mujoco.mj_forward(m, d)
        jac = d.efc_J.reshape(d.nefc, m.nv)
        slopes = {group: jac[d.contact[i].efc_address].copy() for group, i in closest_contacts(m, d).items()}
    mujoco.mj_forward(m, d)
    return slopes


def settle(
    m: mujoco.MjModel,
    d: mujoco.MjData,
    clocks: dict[int, tuple[float, float]],
    steps: int = 400,
    table: PairTable | None = None,
) -> None:
    """Let preloaded contacts sink to their static penetration with the drives held still, then
    give the mechanism its start velocity again (MuJoCo's contact carries load only when it
    penetrates, so an assembled contact at distance zero would start with a jolt). `table`: as
    closest_contacts."""
    start = {dof: (q, 0.0) for dof, (q, _) in clocks.items()}
    for dof, (q, _) in start.items():
        d.qpos[dof], d.qvel[dof] = q, 0.0
    d.qvel[:] = 0.0
    mujoco.mj_step(m, d, steps)
    if not np.isfinite(d.qpos).all():
        raise Singular("the preloaded cam contact does not settle", 0.0)
    d.time = 0.0
    d.qvel[:] = 0.0
    for dof, (q, _) in clocks.items():
        d.qpos[dof] = q
    _, jac = _rows(m, d, table)
    velocities(m, d, jac, {dof: v for dof, (_, v) in clocks.items()})
    mujoco.mj_forward(m, d)
