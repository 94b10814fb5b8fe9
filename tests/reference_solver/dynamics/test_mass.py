"""The mass matrix's diagonal, diag(m, m, J) per body in the layout's column order, and what it
refuses: a body without positive mass or inertia, and (for forward dynamics) a cam's massless
contact parameter."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.errors import SolverError
from reference_solver.layout import Layout
from scenarios import Body, Scenario


def free_bodies(*bodies: Body) -> Scenario:
    return Scenario("free", "default", bodies, (), (), 1.0, 1, 1.0)


def test_each_body_contributes_its_mass_twice_then_its_inertia() -> None:
    scenario = free_bodies(
        Body("a", (0, 0, 0), mass=2.0, inertia=0.3), Body("b", (1, 0, 0), mass=5.0, inertia=7.0)
    )
    diagonal = mass_diagonal(scenario, Layout.of(scenario))
    np.testing.assert_array_equal(diagonal, [2.0, 2.0, 0.3, 5.0, 5.0, 7.0])


@pytest.mark.parametrize(("mass", "inertia"), [(0.0, 1.0), (1.0, 0.0), (-1.0, 1.0), (1.0, -1.0), (0.0, 0.0)])
def test_a_body_without_positive_mass_and_inertia_is_refused_by_name(mass: float, inertia: float) -> None:
    scenario = free_bodies(Body("a", (0, 0, 0)), Body("heavyless", (0, 0, 0), mass=mass, inertia=inertia))
    with pytest.raises(SolverError) as raised:
        mass_diagonal(scenario, Layout.of(scenario))
    assert str(raised.value) == "free: body heavyless needs a positive mass and inertia"


def test_a_cam_contact_is_refused_for_forward_dynamics_and_massless_for_inverse_dynamics() -> None:
    cam = scenarios.build("cam_roller")
    layout = Layout.of(cam)
    assert layout.contacts
    with pytest.raises(SolverError) as raised:
        mass_diagonal(cam, layout)
    assert str(raised.value) == f"{cam.name}: dynamics with cam contacts is not supported"
    diagonal = mass_diagonal(cam, layout, massless_contacts=True)
    expected = np.concatenate(
        [[b.mass, b.mass, b.inertia] for b in cam.bodies] + [np.zeros(len(layout.contacts))]
    )
    np.testing.assert_array_equal(diagonal, expected)
