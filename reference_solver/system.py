"""The stacked constraint system C(q, t) = 0 of a scenario: joints, gears and cams, then drivers."""

from __future__ import annotations

import numpy as np

from reference_solver.equation import Equation
from reference_solver.equations.cams import FlatFaceEquation, KnifeEdgeEquation, RollerEquation
from reference_solver.equations.drivers import (
    AbsoluteDriverEquation,
    PointPathDriverEquation,
    RelativeDisplacementDriverEquation,
    RelativeRotationDriverEquation,
)
from reference_solver.equations.gears import GearPairEquation, RackPinionEquation
from reference_solver.equations.joints import (
    GroundEquation,
    PrismaticEquation,
    RevoluteEquation,
    RevoluteRevoluteEquation,
)
from reference_solver.layout import Layout
from scenarios import cams, drivers, gears, joints
from scenarios.scenario import Constraint, Scenario

EQUATIONS: dict[type, type[Equation]] = {
    joints.Ground: GroundEquation,
    joints.Revolute: RevoluteEquation,
    joints.Prismatic: PrismaticEquation,
    joints.RevoluteRevolute: RevoluteRevoluteEquation,
    gears.GearPair: GearPairEquation,
    gears.RackPinion: RackPinionEquation,
    cams.KnifeEdgeCam: KnifeEdgeEquation,
    cams.RollerCam: RollerEquation,
    cams.FlatFaceCam: FlatFaceEquation,
    drivers.AbsoluteDriver: AbsoluteDriverEquation,
    drivers.RelativeRotationDriver: RelativeRotationDriverEquation,
    drivers.PointPathDriver: PointPathDriverEquation,
    drivers.RelativeDisplacementDriver: RelativeDisplacementDriverEquation,
}


def equation_for(constraint: Constraint, layout: Layout) -> Equation:
    """The equations of one constraint of the scenario vocabulary."""
    try:
        kind = EQUATIONS[type(constraint)]
    except KeyError:
        raise TypeError(f"no equations for constraint type {type(constraint).__name__}") from None
    return kind(constraint, layout)  # type: ignore[call-arg, arg-type]


class ConstraintSystem:
    """C, C_q, C_t and Q_d of every constraint of a scenario, stacked.

    Rows and columns are also available scaled (lengths in units of the characteristic length), the
    form in which tolerances and singularity are judged.
    """

    def __init__(self, scenario: Scenario, include_drivers: bool = True):
        self.scenario = scenario
        self.layout = Layout.of(scenario)
        constraints: tuple[Constraint, ...] = scenario.joints
        if include_drivers:
            constraints = constraints + scenario.drivers
        self.equations = [equation_for(c, self.layout) for c in constraints]
        self.offsets = np.cumsum([0] + [e.size for e in self.equations])
        self.size = int(self.offsets[-1])
        self.unknowns = self.layout.size
        self.labels = [label for e in self.equations for label in e.labels]
        length = self.layout.length_scale
        self.row_scales = np.array([length**p for e in self.equations for p in e.powers], dtype=float)
        self.column_scales = self.layout.column_scales()

    def evaluate(
        self, q: np.ndarray, t: float, qd: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """C, the dense C_q and Q_d at (q, qd, t); Q_d is meaningful only when qd is given."""
        qd = np.zeros_like(q) if qd is None else qd
        c = np.empty(self.size)
        jac = np.zeros((self.size, self.unknowns))
        q_d = np.empty(self.size)
        for eq, start in zip(self.equations, self.offsets, strict=False):
            for k, row in enumerate(eq.constraint_rows(q, qd, t)):
                c[start + k] = row.value
                jac[start + k, eq.columns] = row.jac
                q_d[start + k] = row.q_d
        return c, jac, q_d

    def residual(self, q: np.ndarray, t: float) -> np.ndarray:
        return self.evaluate(q, t)[0]

    def jacobian(self, q: np.ndarray, t: float) -> np.ndarray:
        return self.evaluate(q, t)[1]

    def q_d(self, q: np.ndarray, qd: np.ndarray, t: float) -> np.ndarray:
        return self.evaluate(q, t, qd)[2]

    def c_t(self, t: float) -> np.ndarray:
        return np.concatenate([eq.c_t(t) for eq in self.equations]) if self.equations else np.zeros(0)

    def scaled_jacobian(self, jac: np.ndarray) -> np.ndarray:
        """D_r^-1 C_q D_c: the Jacobian in units of the characteristic length."""
        return jac * self.column_scales[None, :] / self.row_scales[:, None]
