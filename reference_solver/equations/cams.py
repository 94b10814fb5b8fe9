"""Equations of the cam contacts; each has the profile parameter phi as an extra unknown."""

from __future__ import annotations

import numpy as np

from reference_solver.equation import Equation
from reference_solver.kinematic_vectors import (
    ConstraintRow,
    KinematicVector,
    components,
    inner,
    profile_vector,
    translate,
)
from reference_solver.layout import Layout
from scenarios.cam_profiles import profile_point
from scenarios.cams import CamContact, FlatFaceCam, KnifeEdgeCam, RollerCam


class CamEquation(Equation):
    """Shared by the three contacts: the contact point r_cam(phi) and the profile tangent there."""

    def __init__(self, contact: CamContact, layout: Layout, follower: str):
        super().__init__(contact.name, layout, (contact.cam, follower), contact=contact.name)
        self.contact = contact
        self.phi_column = layout.phi_column(contact.name)

    def profile(self, q: np.ndarray, qd: np.ndarray) -> tuple[KinematicVector, KinematicVector]:
        """The contact point on the cam and the tangent A u'(phi)."""
        phi, phi_rate = q[self.phi_column], qd[self.phi_column]
        pose, rate = self.state(q, qd, self.contact.cam)
        col = self.local(self.contact.cam)
        assert self.phi_local is not None
        u = profile_point(self.contact.profile, float(phi))
        point = profile_vector(u, pose, rate, phi_rate, col, self.phi_local, self.width)
        tangent = profile_vector(u[1:], pose, rate, phi_rate, col, self.phi_local, self.width)
        return translate(point, pose, rate, col), tangent


class KnifeEdgeEquation(CamEquation):
    """r_cam(phi) - r_tip = 0."""

    def __init__(self, contact: KnifeEdgeCam, layout: Layout):
        super().__init__(contact, layout, contact.tip.body)
        self.tip = contact.tip
        self.labels = (f"{contact.name}.x", f"{contact.name}.y")
        self.powers = (1, 1)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        point, _ = self.profile(q, qd)
        return components(point - self.point(q, qd, self.tip))


class RollerEquation(CamEquation):
    """n . t = 0 and n . n - r^2 = 0, n = r_centre - r_cam(phi)."""

    def __init__(self, contact: RollerCam, layout: Layout):
        super().__init__(contact, layout, contact.centre.body)
        self.centre = contact.centre
        self.radius = contact.roller_radius
        self.labels = (f"{contact.name}.tangent", f"{contact.name}.distance")
        self.powers = (2, 2)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        point, tangent = self.profile(q, qd)
        n = self.point(q, qd, self.centre) - point
        distance = inner(n, n)
        return inner(n, tangent), ConstraintRow(distance.value - self.radius**2, distance.jac, distance.q_d)


class FlatFaceEquation(CamEquation):
    """h . t = 0 and h . (r_cam(phi) - r_face) = 0, h the face's unit normal."""

    def __init__(self, contact: FlatFaceCam, layout: Layout):
        super().__init__(contact, layout, contact.face.body)
        self.face = contact.face
        nx, ny = contact.normal
        norm = float(np.hypot(nx, ny))
        self.normal = (nx / norm, ny / norm)
        self.labels = (f"{contact.name}.tangent", f"{contact.name}.distance")
        self.powers = (1, 1)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        point, tangent = self.profile(q, qd)
        h = self.direction(q, qd, self.face.body, self.normal)
        return inner(h, tangent), inner(h, point - self.point(q, qd, self.face))
