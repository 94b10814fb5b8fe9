"""The mobility check: a kinematically driven system has exactly as many independent drivers as
the joints leave degrees of freedom, and no redundant joint equations."""

from __future__ import annotations

import numpy as np

from reference_solver.diagnostics import RankReport, rank_report
from reference_solver.errors import MobilityError
from reference_solver.system import ConstraintSystem


def _structural_report(system: ConstraintSystem, q: np.ndarray) -> RankReport:
    """The rank report at q, or at a nearby generic point if q happens to be singular."""
    rng = np.random.default_rng(0)
    best = rank_report(system.scaled_jacobian(system.jacobian(q, 0.0)), system.labels)
    for _ in range(3):
        if best.deficiency == 0:
            break
        point = q + 1e-3 * system.column_scales * rng.standard_normal(q.size)
        report = rank_report(system.scaled_jacobian(system.jacobian(point, 0.0)), system.labels)
        best = report if report.rank > best.rank else best
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
    _refuse_dependent_rows(
        joint_report,
        f"{scenario.name}: redundantly constrained: {joints.size} joint equations but only "
        f"{joint_report.rank} independent",
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
    _refuse_dependent_rows(
        _structural_report(full, q),
        f"{scenario.name}: the drivers ({names}) do not act on independent degrees of freedom",
    )
    return dof


def _refuse_dependent_rows(report: RankReport, problem: str) -> None:
    """Raise MobilityError saying `problem` and naming the dependent rows, if the report has any."""
    if report.deficiency > 0:
        raise MobilityError(
            f"{problem}; dependent rows: {', '.join(report.dependent_rows)}",
            rank_deficiency=report.deficiency,
            dependent_rows=report.dependent_rows,
        )
