"""The native solver seen through the adapter contract, as the runner sees every engine."""

from __future__ import annotations

import numpy as np

import adapters
import scenarios
from adapters.base import Setting
from scenarios.closed_form import exact


def test_reference_runs_through_the_contract() -> None:
    engine = adapters.load("reference")
    scenario = scenarios.build("four_bar", overrides={"steps": 40})
    result = engine.run(scenario)
    assert result.status == "ok" and result.trajectory is not None
    assert result.run_time > 0 and result.build_time >= 0 and result.steps > 0
    np.testing.assert_allclose(result.trajectory.position, exact(scenario).position, atol=1e-12)  # type: ignore[arg-type]


def test_tolerance_ladder_trades_accuracy_for_work() -> None:
    engine = adapters.load("reference")
    scenario = scenarios.build("slider_crank", overrides={"steps": 20})
    truth = exact(scenario).position
    errors, iterations = [], []
    for setting in (Setting.of("newton", tolerance=1e-2), Setting.of("newton", tolerance=1e-12)):
        result = engine.run(scenario, setting)
        assert result.trajectory is not None
        errors.append(float(np.abs(result.trajectory.position - truth).max()))  # type: ignore[operator]
        iterations.append(result.steps)
    assert errors[1] < 1e-14 < errors[0] and iterations[0] < iterations[1]


def test_singular_drive_is_a_singular_status_with_its_time() -> None:
    engine = adapters.load("reference")
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.0})
    result = engine.run(scenario)
    assert result.status == "singular" and result.trajectory is None
    assert result.failure_time is not None and abs(result.failure_time - np.pi / 100) < 1e-9
    assert "dead" in result.message or "singular" in result.message


def test_unknown_mode_fails_cleanly() -> None:
    result = adapters.load("reference").run(scenarios.build("four_bar"), Setting.of("euler"))
    assert result.status == "failed" and "unknown mode 'euler'" in result.message


def test_the_two_native_dynamic_methods_check_each_other_through_the_contract() -> None:
    """Mode ali3p (index-3 augmented Lagrangian, step dt) against mode DOP853 (partitioned, rtol
    1e-12) on the compound pendulum: second order in dt (largest position-level distance over the
    characteristic length, measured 4.10e-5 and 1.02e-5 at dt 1e-3 and 5e-4), each run through the
    runner's contract."""
    engine = adapters.load("reference")
    scenario = scenarios.build("compound_pendulum", overrides={"t_end": 0.5, "steps": 10})
    partitioned = engine.run(scenario, Setting.of("DOP853", rtol=1e-12)).trajectory
    assert partitioned is not None
    distances = []
    for dt in (1e-3, 5e-4):
        result = engine.run(scenario, Setting.of("ali3p", dt=dt))
        assert result.status == "ok" and result.trajectory is not None
        difference = result.trajectory.position - partitioned.position  # type: ignore[operator]
        distances.append(float(np.abs(difference).max()) / scenario.characteristic_length)
    assert 3.8 < distances[0] / distances[1] < 4.2
    assert 1.02e-5 / 3 < distances[1] < 3 * 1.02e-5


def test_the_compiled_and_the_plain_right_hand_side_give_one_motion_through_the_contract() -> None:
    """The native engine's dynamics run the compiled right-hand side unless `compiled=0`: both on
    the four-bar under gravity at rtol 1e-12 agree to rtol's order (positions over the
    characteristic length, velocities and accelerations over their own largest values)."""
    engine = adapters.load("reference")
    scenario = scenarios.build("four_bar_gravity", overrides={"t_end": 0.5, "steps": 20})
    compiled = engine.run(scenario, Setting.of("DOP853", rtol=1e-12)).trajectory
    plain = engine.run(scenario, Setting.of("DOP853", rtol=1e-12, compiled=0)).trajectory
    assert compiled is not None and plain is not None
    for level in ("position", "velocity", "acceleration"):
        a, b = getattr(compiled, level), getattr(plain, level)
        scale = scenario.characteristic_length if level == "position" else float(np.abs(b).max())
        assert 0 < float(np.abs(a - b).max()) / scale < 1e-9, level  # 0: the same path twice


def test_a_kinematic_run_without_inverse_dynamics_names_why_it_gives_no_forces() -> None:
    native = adapters.load("reference")
    scenario = scenarios.build("slider_crank", overrides={"steps": 4})
    run = native.run(scenario, Setting.of("newton", tolerance=1e-10))
    assert run.status == "ok" and run.trajectory is not None
    assert not [c for c in run.trajectory.extras if c.endswith((".force", ".fx", ".fy"))]
    assert any("forces not given: inverse_dynamics=0" in w for w in run.warnings), run.warnings
    assert not any("forces not given" in w for w in native.run(scenario).warnings)
