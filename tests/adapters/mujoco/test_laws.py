"""MuJoCo drives every motion law: polynomials of degree 2 to 4 through polycoef on a unit-rate
clock, tabulated laws and higher polynomials by a steered clock, each against the native solver's
kinematic analysis (an independent truth: absolute coordinates and Newton, no MuJoCo).

Measured (slider-crank and four-bar over 0.125 s, 51 outputs; absolute errors, rad, m and per
second) at RK4, the rule's step, tc = 4 steps with MuJoCo's own regulariser (polycoef's rung of the
ladder; the rule's default, tc = 128 steps with the regulariser scaled, steers the clock):
    slider_crank  quad     polycoef 5.05e-05 3.08e-03 1.03e+00   steered 1.99e-07 1.70e-04 9.90e-01
                  quartic  polycoef 7.04e-05 3.52e-03 1.07e+00   steered 2.49e-07 2.08e-04 1.15e+00
                  quintic                                        steered 3.21e-07 2.43e-04 1.36e+00
                  tab                                            steered 2.23e-09 7.59e-06 1.87e-01
    four_bar      quad     polycoef 5.97e-05 1.05e-02 3.59e+00   steered 3.54e-07 4.50e-04 2.69e+00
                  quartic  polycoef 7.04e-05 1.43e-02 4.60e+00   steered 4.27e-07 5.66e-04 3.18e+00
                  quintic                                        steered 5.06e-07 7.04e-04 3.87e+00
                  tab                                            steered 7.76e-10 7.43e-06 1.98e-01
polycoef's drive lags by P''(c) tc^2 (MuJoCo leaves out dJ/dt v of a joint equality); positions
converge at second order in the step, velocities at first, accelerations sit on the regulariser's
floor whatever the step (adapters.mujoco.weights). The kinematic
mode (Newton on MuJoCo's rows, polycoef's bias read) is exact: at most 1.6e-14 of each level's
largest value.
"""

from __future__ import annotations

import dataclasses
import xml.etree.ElementTree as ET

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from adapters.mujoco import MujocoAdapter
from adapters.mujoco.controls import controls
from adapters.mujoco.settings import own_regulariser
from adapters.mujoco.simulation import soften
from reference_solver import solve
from scenarios import Polynomial, TabulatedLaw
from scenarios.drivers import RelativeRotationDriver
from scenarios.motions import Motion
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory
from tests.support.measured import measured_table

ADAPTER = MujocoAdapter()
LEVELS = ("position", "velocity", "acceleration")
FAMILIES = ("slider_crank", "four_bar")


def law(name: str, start: float) -> Motion:
    """The crank's angle laws tested, from the family's start angle."""
    return {
        "quad": Polynomial((start, 20.0, 400.0)),
        "quartic": Polynomial((start, 10.0, 200.0, 3000.0, -10000.0)),
        "quintic": Polynomial((start, 10.0, 200.0, 3000.0, -10000.0, 20000.0)),
        "tab": TabulatedLaw(
            (0.0, 0.03, 0.06, 0.09, 0.12, 0.15),
            tuple(start + v for v in (0.0, 0.9, 2.3, 3.2, 3.8, 4.2)),
            "clamped",
            (20.0, 10.0),
        ),
    }[name]


def driven(family: str, name: str) -> Scenario:
    """The family over 0.125 s (51 outputs) with its crank driven by the law `name`."""
    base = scenarios.build(family, overrides={"steps": 50})
    drive = base.drivers[0]
    start = drive.motion.start  # type: ignore[union-attr]
    motion = law(name, start)
    return dataclasses.replace(base, drivers=(dataclasses.replace(drive, motion=motion),), t_end=0.125)


def errors(scenario: Scenario, setting: Setting | None) -> dict[str, float]:
    """Largest absolute error per level against the native solver."""
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    return difference(result.trajectory, solve(scenario))


def difference(got: Trajectory, truth: Trajectory) -> dict[str, float]:
    expected = truth.select(got.bodies)
    return {level: float(np.abs(got.level(level) - expected.level(level)).max()) for level in LEVELS}  # type: ignore[operator]


@pytest.mark.parametrize("name", ("quad", "quartic", "quintic", "tab"))
def test_every_law_is_supported(name: str) -> None:
    assert ADAPTER.supports(driven("slider_crank", name)) is None


def test_polynomials_up_to_quartic_are_polycoef_on_a_unit_rate_clock() -> None:
    for name, powers in (("quad", (20.0, 400.0, 0.0, 0.0)), ("quartic", (10.0, 200.0, 3000.0, -10000.0))):
        model = ADAPTER.build(driven("slider_crank", name), Setting.of("RK4"))
        root = ET.fromstring(model.xml)
        drive = root.find("equality/joint[@name='crank_drive']")
        assert drive is not None and drive.get("joint2") == "clock_crank_drive"
        a = [float(v) for v in drive.get("polycoef", "").split()]
        assert abs(a[0]) < 1e-12 and a[1:] == list(powers)  # the crank's hinge has coefficient 1
        assert root.find("actuator") is None
        (clock,) = model.clocks.values()
        assert (clock.q0, clock.v0, clock.law) == (0.0, 1.0, None)


@pytest.mark.parametrize("name", ("quintic", "tab"))
def test_other_laws_are_clocks_steered_by_a_motor(name: str) -> None:
    scenario = driven("slider_crank", name)
    model = ADAPTER.build(scenario, Setting.of("RK4"))
    root = ET.fromstring(model.xml)
    drive = root.find("equality/joint[@name='crank_drive']")
    assert drive is not None
    assert [float(v) for v in drive.get("polycoef", "").split()][2:] == [0.0, 0.0, 0.0]
    motor = root.find("actuator/motor[@name='clock_crank_drive']")
    assert motor is not None and motor.get("joint") == "clock_crank_drive"
    m, dof = model.model, next(iter(model.clocks))
    assert float(motor.get("gear", "")) == m.dof_armature[dof] + 1.0  # the control is f''
    (clock,) = model.clocks.values()
    assert clock.law == scenario.drivers[0].motion


@pytest.mark.parametrize("name", ("quad", "quartic", "quintic", "tab"))
@pytest.mark.parametrize("family", FAMILIES)
def test_kinematic_mode_is_exact_for_every_law(family: str, name: str) -> None:
    scenario = driven(family, name)
    result = ADAPTER.run(scenario, Setting.of("kinematic"))
    assert result.status == "ok" and result.trajectory is not None, result.message
    truth = solve(scenario)
    found = difference(result.trajectory, truth)
    for level in LEVELS:
        size = float(np.abs(truth.level(level)).max())  # type: ignore[arg-type]
        assert found[level] < 1e-13 * size, (level, found[level] / size)  # measured <= 1.6e-14


BOUNDS: dict[tuple[str, str, str], tuple[float, ...]] = measured_table("mujoco_law_bounds")
"""Three times the measured errors (module docstring), absolute."""


@pytest.mark.parametrize(("family", "name", "way"), sorted(BOUNDS))
def test_rk4_default_against_the_native_solver(family: str, name: str, way: str) -> None:
    scenario = driven(family, name)
    setting = ADAPTER.default_setting(scenario).replace(polynomial=way)
    if way == "polycoef":  # its rung of the ladder: MuJoCo's own regulariser, tc 4 steps
        setting = own_regulariser(setting)
        assert setting in ADAPTER.ladder(scenario)
    found = errors(scenario, setting)
    for level, bound in zip(LEVELS, BOUNDS[family, name, way], strict=True):
        assert found[level] < bound, (level, found[level], bound)


@pytest.mark.parametrize(("name", "way"), (("quad", "polycoef"), ("quartic", "steered"), ("tab", "steered")))
def test_error_drops_as_the_step_is_refined(name: str, way: str) -> None:
    """With MuJoCo's own regulariser, a quarter of the step (tc kept at 4 steps): positions 16 times
    closer (measured 15.7-16.0), velocities at least 4 times (measured 4.0-18.6); accelerations stay
    on the regulariser's floor."""
    scenario = driven("slider_crank", name)
    base = own_regulariser(ADAPTER.default_setting(scenario)).replace(polynomial=way)
    fine = base.replace(dt=float(base["dt"]) / 4, tc=float(base["tc"]) / 4)
    coarse, refined = errors(scenario, base), errors(scenario, fine)
    assert refined["position"] < coarse["position"] / 10.0
    assert refined["velocity"] < coarse["velocity"] / 3.0


def clock_errors(mode: str) -> tuple[float, float]:
    """The steered clock's largest (angle, rate) error from its law over 5000 steps of the
    tabulated drive (the rule's step, 1.5e-5 s), under MuJoCo's integrator `mode`."""
    scenario = driven("slider_crank", "tab")
    model = ADAPTER.build(scenario, Setting(mode, ADAPTER.default_setting(scenario).options))
    m = model.model
    soften(m, model)
    d = mujoco.MjData(m)
    d.qpos[:], d.qvel[:] = model.qpos0, model.qvel0
    ((dof, clock),) = model.clocks.items()
    angle = rate = 0.0
    with controls(m, d, (), model.clocks):
        for _ in range(100):
            mujoco.mj_step(m, d, 50)
            q, v = clock.at(d.time)
            angle, rate = max(angle, abs(d.qpos[dof] - q)), max(rate, abs(d.qvel[dof] - v))
    return angle, rate


def test_the_steered_clock_follows_its_law_at_every_stage() -> None:
    """RK4 reads the control at its stage times, so a clock whose f'' is piecewise linear (a cubic
    spline) is integrated to round-off (measured 5.3e-12 rad, 1.3e-10 rad/s); Euler reads it once
    per step and lags by O(h) (measured 2.9e-4 rad, 1.2e-2 rad/s)."""
    angle, rate = clock_errors("RK4")
    assert angle < 2e-11 and rate < 5e-10, (angle, rate)
    angle, rate = clock_errors("Euler")
    assert angle > 1e-4 and rate > 5e-3, (angle, rate)


def test_the_control_callback_is_cleared_after_every_run() -> None:
    assert mujoco.get_mjcb_control() is None
    assert ADAPTER.run(driven("slider_crank", "tab")).status == "ok"
    assert mujoco.get_mjcb_control() is None
    model = ADAPTER.build(driven("four_bar", "quintic"), Setting.of("RK4"))
    d = mujoco.MjData(model.model)
    with pytest.raises(RuntimeError), controls(model.model, d, (), model.clocks):
        assert mujoco.get_mjcb_control() is not None
        raise RuntimeError("a run that fails midway")
    assert mujoco.get_mjcb_control() is None


def test_a_run_without_steered_clocks_sets_no_callback() -> None:
    model = ADAPTER.build(driven("slider_crank", "quad"), Setting.of("RK4"))
    with controls(model.model, mujoco.MjData(model.model), (), model.clocks):
        assert mujoco.get_mjcb_control() is None


@pytest.mark.parametrize("degree", (3, 5))
def test_a_drive_over_two_joints_is_a_tendon_equality(degree: int) -> None:
    """The rocker's angle relative to the crank (two hinges of the tree): a fixed tendon over them
    tied to the clock's own tendon by polycoef (degree 3) or linearly to a steered clock (degree 5);
    the kinematic mode exact (measured 8.9e-16, 2.8e-14, 6.3e-13 absolute)."""
    base = scenarios.build("four_bar", overrides={"steps": 50})
    start = solve(base).position[0]
    rel0 = float(start[base.output_bodies.index("rocker"), 2] - start[base.output_bodies.index("crank"), 2])
    coefficients = (rel0, 2.0, 30.0, -40.0, 10.0, 5.0)[: degree + 1]
    drive = RelativeRotationDriver("rel", "rocker", "crank", Polynomial(coefficients))
    scenario = dataclasses.replace(base, drivers=(drive,), t_end=0.1)
    model = ADAPTER.build(scenario, Setting.of("kinematic"))
    tendon = ET.fromstring(model.xml).find("equality/tendon[@name='rel']")
    assert tendon is not None and (tendon.get("tendon2") == "rel_clock") == (degree <= 4)
    result = ADAPTER.run(scenario, Setting.of("kinematic"))
    assert result.trajectory is not None, result.message
    truth = solve(scenario)
    found = difference(result.trajectory, truth)
    for level in LEVELS:
        assert found[level] < 1e-13 * float(np.abs(truth.level(level)).max()), level  # type: ignore[arg-type]
