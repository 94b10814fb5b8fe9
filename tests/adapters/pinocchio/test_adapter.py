"""The Pinocchio adapter's kinematic mode on every family: closed forms where they exist, the
reference solver for spline cams, and both gear representations (mimic joints and coupling rows).

Bounds are what Pinocchio's Newton solve really reaches, with a margin (measured maxima over one
revolution: position 2e-14, velocity 7e-14, acceleration 2e-11, contact parameter 1e-13)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import scenarios
from adapters import load
from adapters.base import Setting
from adapters.pinocchio import PinocchioAdapter
from reference_solver import solve
from scenarios.closed_form import exact

BOUNDS = {"position": 1e-12, "velocity": 1e-11, "acceleration": 1e-10}
PHI_BOUND = 1e-12
DISC = [n for n in scenarios.catalogue() if not n.endswith("/spline")]
SPLINE = [n for n in scenarios.catalogue() if n.endswith("/spline")]
GEARS = ["spur_gears", "spur_gears/internal", "planetary_gears"]


def max_errors(result, truth) -> dict[str, float]:  # type: ignore[no-untyped-def]
    truth = truth.select(result.bodies)
    return {lv: float(np.max(np.abs(result.level(lv) - truth.level(lv)))) for lv in BOUNDS}


def run_ok(name: str, **options: object):  # type: ignore[no-untyped-def]
    adapter = PinocchioAdapter()
    scenario = scenarios.build(name)
    setting = adapter.default_setting(scenario).replace(**options)  # type: ignore[arg-type]
    result = adapter.run(scenario, setting)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    return scenario, result


def test_registered_under_its_name() -> None:
    adapter = load("pinocchio")
    assert isinstance(adapter, PinocchioAdapter) and adapter.name == "pinocchio"
    assert adapter.version().count(".") >= 1


@pytest.mark.parametrize("name", DISC)
def test_kinematic_mode_matches_closed_form(name: str) -> None:
    scenario, result = run_ok(name)
    trajectory = result.trajectory
    assert trajectory.bodies == scenario.output_bodies
    assert trajectory.levels == ("position", "velocity", "acceleration")
    errors = max_errors(trajectory, exact(scenario, trajectory.times))
    assert all(errors[lv] < BOUNDS[lv] for lv in BOUNDS), errors
    assert result.steps == len(trajectory.times)
    for contact in scenario.cams:
        key = f"{contact.name}.phi"
        phi_error = np.max(np.abs(trajectory.extras[key] - exact(scenario, trajectory.times).extras[key]))
        assert phi_error < PHI_BOUND


@pytest.mark.parametrize("name", SPLINE)
def test_spline_cams_match_the_reference_solver(name: str) -> None:
    adapter = PinocchioAdapter()
    scenario = scenarios.build(name, overrides={"steps": 60})
    result = adapter.run(scenario)
    assert result.status == "ok", result.message
    trajectory = result.trajectory
    assert trajectory is not None
    reference = solve(scenario, trajectory.times)
    errors = max_errors(trajectory, reference)
    assert all(errors[lv] < BOUNDS[lv] for lv in BOUNDS), errors
    phi = np.max(np.abs(trajectory.extras["contact.phi"] - reference.extras["contact.phi"]))
    assert phi < PHI_BOUND


@pytest.mark.parametrize("name", GEARS)
def test_gears_as_coupling_rows_match_closed_form(name: str) -> None:
    scenario, result = run_ok(name, gears="row")
    errors = max_errors(result.trajectory, exact(scenario, result.trajectory.times))
    assert all(errors[lv] < BOUNDS[lv] for lv in BOUNDS), errors


@pytest.mark.parametrize("name", GEARS)
def test_gear_pairs_become_mimic_joints(name: str) -> None:
    """With mimic joints the driven gear train has a single coordinate and no loop rows."""
    adapter = PinocchioAdapter()
    scenario = scenarios.build(name)
    mimic = adapter.build(scenario, adapter.default_setting(scenario))
    rows = adapter.build(scenario, adapter.default_setting(scenario).replace(gears="row"))
    assert mimic.pm.model.nq == 1 and mimic.pm.tree.closures == () and len(mimic.pm.tree.mimics) == 1
    assert rows.pm.model.nq == 2 and rows.pm.tree.closures == ("mesh",)


def test_loose_tolerance_costs_accuracy() -> None:
    """The ladder's tolerances really trade accuracy: a 1e-5 residual bound leaves errors near it."""
    scenario, loose = run_ok("four_bar", tol=1e-5)
    _, tight = run_ok("four_bar")
    truth = exact(scenario, tight.trajectory.times)
    loose_error = max_errors(loose.trajectory, truth)["position"]
    tight_error = max_errors(tight.trajectory, truth)["position"]
    assert 1e-12 < loose_error < 1e-3 and tight_error < 1e-13


def test_angles_are_continuous_over_revolutions() -> None:
    _, result = run_ok("planetary_gears")
    planet = result.trajectory.position[:, result.trajectory.bodies.index("planet"), 2]
    assert planet[-1] - planet[0] == pytest.approx(3 * 2 * np.pi, abs=1e-12)  # (1 + 0.06 / 0.03) turns
    assert np.all(np.diff(planet) > 0)


def test_export_writes_a_model_pinocchio_reloads(tmp_path: Path) -> None:
    adapter = PinocchioAdapter()
    scenario = scenarios.build("planetary_gears")
    target = tmp_path / "planetary.xml"
    adapter.export(scenario, adapter.default_setting(scenario), str(target))
    model = pin.Model()
    model.loadFromXML(str(target), "model")
    assert model.nq == 1  # the planet mimics the arm
    assert {"arm", "planet"} <= {frame.name for frame in model.frames}


def test_scenes_carry_no_gravity() -> None:
    for mode in ("kinematic", "dynamic"):
        built = PinocchioAdapter().build(scenarios.build("slider_crank"), Setting.of(mode))
        assert np.all(built.pm.model.gravity.vector == 0.0)
