"""Exudyn's driving forces and reactions (SensorObject Force on the driver's coordinate connector
and the revolute joints, ForceLocal on the prismatic joints) against the native solver's, at
measured bounds, t = 0 included."""

from __future__ import annotations

import exudyn as exu
import numpy as np
import pytest

import adapters
from adapters.base import Setting
from adapters.exudyn.force_sensors import add_force_sensors
from reports.scoring.comparison import measure
from reports.scoring.forces import native_forces
from reports.scoring.truth import independent_truth
from scenarios import load
from tests.support.bounds import held
from tests.support.measured import EXUDYN_FORCES

EXUDYN = adapters.load("exudyn")


def _run(name: str, setting: Setting | None, overrides: dict[str, object]):
    scenario = load(name, overrides)
    times = np.asarray(scenario.times())
    run = EXUDYN.run(scenario, setting, times)
    assert run.status == "ok", run.message
    return scenario, times, run


@pytest.mark.parametrize(("name", "mode"), list(EXUDYN_FORCES))
def test_forces_match_the_native_inverse_dynamics(name: str, mode: str) -> None:
    setting = EXUDYN.default_setting(load(name))
    scenario, times, run = _run(name, Setting.of(mode, **dict(setting.options)), {})
    metrics, _, _ = measure(scenario, run, independent_truth(scenario, times).trajectory, None)
    held([metrics["error_force"]], [EXUDYN_FORCES[(name, mode)]], ("force",))
    assert np.isfinite(metrics["driver_force_error"]) and np.isfinite(metrics["reaction_error"])


@pytest.mark.parametrize("run_in", [None, 0])
def test_the_start_s_forces_are_exudyn_s_own_not_zero(run_in: int | None) -> None:
    """Exudyn records a start it did not solve as zero force: without a run-in the adapter's first
    step solves it (to 1e-6 of the scale); after one the start is a step of the run (GA3's own
    error there, 2.3e-6)."""
    setting = None if run_in is None else EXUDYN.default_setting(load("slider_crank")).replace(run_in=run_in)
    scenario, times, run = _run("slider_crank", setting, {"steps": 12})
    native = native_forces(scenario, times)
    assert run.trajectory is not None
    torque = run.trajectory.extras["crank_drive.force"]
    bound = 1e-6 if run_in == 0 else 1e-5
    assert abs(torque[0] - native["crank_drive.force"][0]) < bound * np.max(
        np.abs(native["crank_drive.force"])
    )


PRISMATIC = {("slider_crank", "slide"): 1.2e-6, ("cam_roller", "guide"): 1.7e-7}
"""(scenario, prismatic joint): the error of its reaction (both components, over the mechanism's
force scale, scoring.forces) at the default, measured: Exudyn's ForceLocal, in the
marker-0 body's axes, turned into world axes. The slider's axis is x, the follower's y, so a
mapping that took the joint's axial and normal components for x and y would fail the second."""


@pytest.mark.parametrize(("name", "joint"), list(PRISMATIC))
def test_a_prismatic_joint_s_reaction_matches_the_native_inverse_dynamics(name: str, joint: str) -> None:
    scenario, times, run = _run(name, None, {})
    native = native_forces(scenario, times)
    assert run.trajectory is not None
    scale = max(float(np.max(np.abs(v))) for v in native.values())
    found = max(
        float(np.max(np.abs(run.trajectory.extras[f"{joint}{axis}"] - native[f"{joint}{axis}"])))
        for axis in (".fx", ".fy")
    )
    held([found / scale], [PRISMATIC[(name, joint)]], ("reaction",))


def test_scaled_masses_report_no_forces() -> None:
    _, _, run = _run("slider_crank", Setting.of("GA3", mass_scale=2.0), {"steps": 4})
    assert run.trajectory is not None
    assert "crank_drive.force" not in run.trajectory.extras
    assert any("forces not given: masses scaled" in w for w in run.warnings), run.warnings


def test_exudyn_s_prismatic_force_local_is_in_the_marker_0_body_s_axes() -> None:
    """The convention adapters.exudyn.force_sensors turns into world axes: a body turned by 0.5 rad,
    sliding on a horizontal guide under gravity, carries the guide's force (0, m g) in world axes,
    which Exudyn's ForceLocal gives as (m g sin 0.5, m g cos 0.5): the body's axes."""
    import exudyn as exu
    from exudyn.itemInterface import (
        LoadMassProportional,
        MarkerBodyMass,
        MarkerBodyRigid,
        NodeRigidBody2D,
        ObjectGround,
        ObjectJointPrismatic2D,
        ObjectRigidBody2D,
    )

    from adapters.exudyn.simulation import quiet, simulation_settings

    angle, mass, g = 0.5, 2.0, 9.81
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(
        NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0], initialCoordinates=[0.0, 0.0, angle])
    )
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=0.1))
    mbs.AddLoad(
        LoadMassProportional(
            markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=body)), loadVector=[0, -g, 0]
        )
    )
    joint = mbs.AddObject(
        ObjectJointPrismatic2D(
            markerNumbers=[
                mbs.AddMarker(MarkerBodyRigid(bodyNumber=body)),
                mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground)),
            ],
            axisMarker0=[np.cos(angle), -np.sin(angle), 0.0],
            normalMarker1=[0.0, 1.0, 0.0],
        )
    )
    mbs.Assemble()
    settings = simulation_settings(1e-12)
    settings.timeIntegration.numberOfSteps, settings.timeIntegration.endTime = 10, 0.01
    with quiet():
        mbs.SolveDynamic(settings)
    local = np.asarray(mbs.GetObjectOutput(joint, exu.OutputVariableType.ForceLocal))[:2]
    np.testing.assert_allclose(local, mass * g * np.array([np.sin(angle), np.cos(angle)]), rtol=1e-9)


def test_a_driver_built_without_one_force_object_is_named() -> None:
    """A driver whose Exudyn build is not one object with a force output gets no sensor, and the
    warning (the row's) names it and why."""
    driver = load("slider_crank").drivers[0]
    container = exu.SystemContainer()
    mbs = container.AddSystem()
    with pytest.warns(UserWarning, match=rf"forces not given: '{driver.name}' \(built as 2 Exudyn objects\)"):
        assert add_force_sensors(mbs, {driver.name: (driver, [0, 1])}) == []


def test_the_static_solve_names_why_it_gives_no_forces() -> None:
    _, _, run = _run("slider_crank", Setting.of("STATIC"), {"steps": 4})
    assert run.trajectory is not None and "crank_drive.force" not in run.trajectory.extras
    assert any("forces not given: the static solve" in w for w in run.warnings), run.warnings
