"""The mobility check: a kinematically driven system has exactly as many independent drivers as
the joints leave degrees of freedom, and no redundant joint equations."""

from __future__ import annotations

import numpy as np

from reference_solver.diagnostics import rank_report
from reference_solver.errors import MobilityError
from reference_solver.system import ConstraintSystem


def _structural_report(system: ConstraintSystem, q: np.ndarray):  # type: ignore[no-untyped-def]
    """The rank report at q, or at a nearby generic point if q happens to be singular."""
    rng = np.random.default_rng(0)
    best = None
    for attempt in range(4):
        point = q if attempt == 0 else q + 1e-3 * system.column_scales * rng.standard_normal(q.size)
        jac = system.scaled_jacobian(system.jacobian(point, 0.0))
        report = rank_report(jac, system.labels)
        if best is None or report.rank > best.rank:
            best = report
        if report.deficiency == 0:
            break
    return best


def check_mobility(full: ConstraintSystem, q: np.ndarray) -> int:
    """Raise MobilityError unless the drivers use up every degree of freedom the joints leave.

    Returns the number of degrees of freedom the joints leave. Ranks are judged at q and, should q
    be a singular configuration, at nearby generic points.
    """
    scenario = full.scenario
    joints = ConstraintSystem(scenario, include_drivers=False)
    n = full.unknowns
    joint_report = _structural_report(joints, q)
    if joint_report.deficiency > 0:
        raise MobilityError(
            f"{scenario.name}: redundantly constrained: {joints.size} joint equations but only "
            f"{joint_report.rank} independent; dependent rows: {', '.join(joint_report.dependent_rows)}",
            rank_deficiency=joint_report.deficiency,
            dependent_rows=joint_report.dependent_rows,
        )
    dof = n - joint_report.rank
    driver_rows = full.size - joints.size
    names = ", ".join(d.name for d in scenario.drivers) or "none"
    if driver_rows != dof:
        kind = "over-driven" if driver_rows > dof else "under-driven"
        raise MobilityError(
            f"{scenario.name}: {kind}: {driver_rows} driver equations ({names}) for {dof} "
            f"degree(s) of freedom left by the joints"
        )
    full_report = _structural_report(full, q)
    if full_report.deficiency > 0:
        raise MobilityError(
            f"{scenario.name}: the drivers ({names}) do not act on independent degrees of freedom; "
            f"dependent rows: {', '.join(full_report.dependent_rows)}",
            rank_deficiency=full_report.deficiency,
            dependent_rows=full_report.dependent_rows,
        )
    return dof
