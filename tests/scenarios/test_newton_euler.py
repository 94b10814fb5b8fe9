"""Newton-Euler body by body on a motion (scenarios.newton_euler): on the closed forms it is the
force truth, checked here against the native inverse dynamics it replaces as that truth (a
different derivation: Lagrange multipliers of the constraint Jacobian), and on the native dynamic
truths against the multipliers they carry."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver import analyse
from reference_solver.dynamics import inverse_dynamics, simulate
from scenarios.closed_form import exact
from scenarios.newton_euler import NoForceTruth, body_forces
from scenarios.registry import build


def _relative(found: dict[str, np.ndarray], reference: dict[str, np.ndarray]) -> float:
    """The largest difference over the reference's force columns, over its largest force."""
    columns = [k for k in reference if k.endswith((".fx", ".fy", ".force"))]
    assert columns and set(columns) <= set(found)
    scale = max(float(np.max(np.abs(reference[k]))) for k in columns)
    return max(float(np.max(np.abs(found[k] - reference[k]))) for k in columns) / scale


@pytest.mark.parametrize(
    "name",
    [
        "slider_crank",
        "slider_crank/offset",
        "slider_crank/slider_drive",
        "four_bar",
        "four_bar/crossed",
        "planetary_gears",
    ],
)
def test_the_closed_form_forces_are_the_native_inverse_dynamics(name: str) -> None:
    scenario = build(name)
    times = scenario.times()
    native = inverse_dynamics(scenario, analyse(scenario, times, tolerance=1e-12))
    assert _relative(body_forces(scenario, exact(scenario, times)), native) < 1e-10


@pytest.mark.parametrize("name", ["four_bar_gravity", "andrews_squeezer"])
def test_on_a_dynamic_motion_they_are_the_multipliers_the_motion_was_made_with(name: str) -> None:
    """Free dynamics: more body equations than unknowns, consistent on a true motion (gravity, a
    spring and a motor torque among the loads)."""
    scenario = build(name)
    truth = simulate(scenario, scenario.times(), 1e-12).trajectory()
    assert _relative(body_forces(scenario, truth), truth.extras) < 1e-10


def test_a_crank_alone_needs_the_torque_of_its_angular_acceleration() -> None:
    """The slider-crank's crank driven at constant speed with the rod and slider massless and the
    crank's inertia about its pivot: no torque (no angular acceleration), and the pivot holds the
    centripetal force m omega^2 l / 2 towards O."""
    import dataclasses

    scenario = build("slider_crank")
    bodies = tuple(
        b if b.name == "crank" else dataclasses.replace(b, mass=0.0, inertia=0.0) for b in scenario.bodies
    )
    light = dataclasses.replace(scenario, bodies=bodies)
    times = scenario.times()
    found = body_forces(light, exact(scenario, times))
    crank = scenario.body("crank")
    omega, length = 50.0, 0.2
    theta = exact(scenario, times).position[:, 0, 2]
    centripetal = crank.mass * omega**2 * length / 2
    assert np.max(np.abs(found["crank_drive.force"])) < 1e-12 * centripetal * length
    assert np.allclose(found["O.fx"], -centripetal * np.cos(theta), rtol=0, atol=1e-10 * centripetal)
    assert np.allclose(found["O.fy"], -centripetal * np.sin(theta), rtol=0, atol=1e-10 * centripetal)


def test_an_element_without_a_free_body_model_is_named() -> None:
    scenario = build("rack_pinion")
    with pytest.raises(NoForceTruth, match="RackPinion 'mesh'"):
        body_forces(scenario, exact(scenario, scenario.times()))
