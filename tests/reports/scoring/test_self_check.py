"""An ok run that drifted says so by its own figures, with no truth: hand-made verdicts, the scenes
whose T + V must stay constant, a doctored trajectory caught, the energy balance with the drivers'
and loads' work, step halving, a gross drift warned about by `solve`, and no alarm on the engines'
default runs (measured margins: energy balances at most 4.9e-3 against the 1e-2 limit, Exudyn's
four-bar with its start-up transient in the driving torque, the others at most 1.5e-3; residuals
at most 8.9e-10 against 1e-3)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from adapters import load as load_engine
from reference_solver.dynamics import simulate
from reports.cli.main import main
from reports.scoring import self_check
from reports.scoring.energy_drift import energy_scale, kinetic_energy
from scenarios.trajectory import Trajectory
from tests.support.engines import ENGINES


def test_the_verdict_names_what_drifted_and_its_limit() -> None:
    assert self_check.verdict(1e-9, 1e-6) == ""
    assert self_check.verdict(math.nan, math.nan) == ""  # not measured is no alarm
    assert self_check.verdict(2e-3, math.nan) == "drifted: constraint residual 0.002 (limit 0.001)"
    both = self_check.verdict(2e-3, 0.5)
    assert both.startswith("drifted: constraint residual") and "T + V changed by 0.5" in both
    assert "not finite" in self_check.verdict(math.inf, math.nan)


@pytest.mark.parametrize(
    ("name", "conservative"),
    [
        ("four_bar_gravity", True),
        ("compound_pendulum", True),
        ("stiff_spring", True),
        ("stiff_spring/damped", False),
        ("andrews_squeezer", False),
        ("four_bar", False),
    ],
)
def test_which_scenes_keep_t_plus_v(name: str, conservative: bool) -> None:
    assert self_check.conservative(scenarios.build(name)) is conservative


def test_the_native_truth_keeps_its_energy_and_a_doctored_one_does_not() -> None:
    scenario = dataclasses.replace(scenarios.build("compound_pendulum"), t_end=0.5, steps=25)
    truth = simulate(scenario, np.asarray(scenario.times()), 1e-12).trajectory()
    assert self_check.energy_change(scenario, truth) < 1e-9
    assert truth.velocity is not None
    doctored = Trajectory(
        truth.times,
        truth.bodies,
        truth.position,
        truth.velocity * np.linspace(1, 1.2, 26)[:, None, None],
        truth.acceleration,
    )
    change = self_check.energy_change(scenario, doctored)
    assert change > self_check.ENERGY_LIMIT
    assert "T + V changed" in self_check.verdict(0.0, change)


def test_solve_warns_on_a_gross_drift_and_keeps_exit_0(capsys, tmp_path) -> None:
    argv = [
        "solve",
        "four_bar_gravity",
        "--engine",
        "mujoco",
        "--mode",
        "Euler",
        "--setting",
        "dt=0.00215818",
    ]
    assert main([*argv, "--out", str(tmp_path / "x.csv")]) == 0
    err = capsys.readouterr().err
    assert err.startswith("mbxval: warning: mujoco drifted: constraint residual") and err.count("\n") == 1


ENERGY_MARGIN = {"drake": 3.0}
"""How far below ENERGY_LIMIT an engine's default run keeps its energy balance on four_bar_gravity,
where not 1000: Drake's SAP step is first order and dissipates (2.9e-3 of the energy scale at its
default step, 2.9e-4 at a tenth of it), and SAP is the only Drake solver that closes a loop."""


@pytest.mark.parametrize("engine", ENGINES)
def test_no_alarm_on_a_default_run(engine: str) -> None:
    scenario = scenarios.build("four_bar_gravity")
    adapter = load_engine(engine)
    if adapter.supports(scenario) is not None or not adapter.dynamics:
        pytest.skip(f"{engine} does not run {scenario.name}")
    result = adapter.run(scenario, adapter.default_setting(scenario), np.asarray(scenario.times()))
    assert result.status == "ok" and result.trajectory is not None
    assert self_check.of_trajectory(scenario, result.trajectory) == ""
    margin = ENERGY_MARGIN.get(engine, 1000.0)
    assert self_check.energy_change(scenario, result.trajectory) < self_check.ENERGY_LIMIT / margin


@pytest.mark.parametrize(
    ("residual", "energy", "drifted"),
    [
        (0.99e-3, math.nan, False),
        (1.01e-3, math.nan, True),
        (0.0, 0.99e-2, False),
        (0.0, 1.01e-2, True),
    ],
)
def test_each_limit_is_pinned_by_a_case_just_inside_and_just_outside(
    residual: float, energy: float, drifted: bool
) -> None:
    """The documented limits (README: residual 1e-3, energy 1e-2), written here as numbers so that a
    changed limit is caught."""
    assert bool(self_check.verdict(residual, energy)) is drifted


def _driven_truth() -> tuple[scenarios.Scenario, Trajectory]:
    """The slider-crank's closed form with its Newton-Euler driving torque: an exact run."""
    from reports.scoring.truth import independent_truth

    scenario = scenarios.build("slider_crank")
    return scenario, independent_truth(scenario, np.asarray(scenario.times())).trajectory


def test_a_driven_run_balances_its_drivers_work_and_a_biased_torque_breaks_it() -> None:
    """The driver's work from its torque balances T; a constant bias b adds b * omega * t to the work,
    which the balance shows as b * omega * t_end over the energy scale: pinned just inside and just
    outside ENERGY_LIMIT."""
    scenario, truth = _driven_truth()
    exact = self_check.energy_change(scenario, truth)
    assert exact < 1e-5  # third-order quadrature on 200 steps a revolution
    scale = max(float(np.max(kinetic_energy(scenario, truth))), energy_scale(scenario, truth))
    angle = 50.0 * scenario.t_end

    def biased(fraction: float) -> float:
        bias = fraction * self_check.ENERGY_LIMIT * scale / angle
        extras = {**truth.extras, "crank_drive.force": truth.extras["crank_drive.force"] + bias}
        return self_check.energy_change(scenario, dataclasses.replace(truth, extras=extras))

    assert biased(0.9) < self_check.ENERGY_LIMIT < biased(1.1)
    assert "T + V changed" in self_check.verdict(0.0, biased(1.1))


def test_a_driven_run_without_its_driving_force_has_no_balance() -> None:
    scenario, truth = _driven_truth()
    bare = dataclasses.replace(truth, extras={})
    assert math.isnan(self_check.energy_change(scenario, bare))


def test_andrews_motor_work_balances_to_fourth_order_and_a_lost_turn_does_not() -> None:
    """Andrews' motor torque and spring: the native truth's balance (Hermite quadrature with its
    accelerations) stays under 1e-3 on the 30-step grid; the same run with the motor's body turned
    at 0.9 of its rate (a run that lost work) is marked."""
    scenario = scenarios.build("andrews_squeezer")
    truth = simulate(scenario, np.asarray(scenario.times()), 1e-12).trajectory()
    assert self_check.energy_change(scenario, truth) < 1e-3
    assert truth.velocity is not None
    slowed = truth.velocity.copy()
    slowed[:, truth.bodies.index("k1"), 2] *= 0.9
    lost = self_check.energy_change(scenario, dataclasses.replace(truth, velocity=slowed))
    assert lost > self_check.ENERGY_LIMIT


def test_the_step_halving_limit_is_pinned_on_each_side() -> None:
    limit = self_check.STEP_LIMIT
    assert self_check.verdict(0.0, 0.0, 0.99 * limit) == ""
    assert self_check.verdict(0.0, 0.0, 1.01 * limit).startswith("drifted: positions moved by")
    assert self_check.verdict(0.0, 0.0, math.inf).startswith("drifted: positions moved by inf")


@pytest.mark.parametrize(("halving", "drifted"), [(0.99e-2, False), (1.01e-2, True)])
def test_the_step_halving_limit_is_1e_2_written_as_a_number(halving: float, drifted: bool) -> None:
    """The documented limit (README: positions that move by more than 1e-2 at half the step) as a
    number, so that a changed STEP_LIMIT is caught (the test above reads the constant and follows it)."""
    assert bool(self_check.verdict(0.0, 0.0, halving)) is drifted


def _andrews_on_mujoco(stiffness: float) -> float:
    scenario = scenarios.build("andrews_squeezer", overrides={"spring_stiffness": stiffness})
    adapter = load_engine("mujoco")
    setting = adapter.default_setting(scenario).replace(dt=5e-5)
    times = np.asarray(scenario.times())
    run = adapter.run(scenario, setting, times)
    assert run.status == "ok" and run.trajectory is not None
    return self_check.step_halving(adapter, scenario, setting, times, run.trajectory)


def test_step_halving_catches_andrews_past_mujocos_stability_limit() -> None:
    """At 1e6 N/m and dt = 5e-5 s RK4 is past its limit: the run ends ok about 146 characteristic
    lengths off its truth, its residual under its limit; at half the step it moves as far (measured
    146). At the test set's 4530 N/m the same step moves it by 2e-5."""
    assert _andrews_on_mujoco(1e6) > 100 * self_check.STEP_LIMIT
    assert _andrews_on_mujoco(4530.0) < self_check.STEP_LIMIT / 100


def test_a_setting_without_a_step_is_not_halved() -> None:
    scenario = scenarios.build("four_bar")
    adapter = load_engine("pinocchio")
    setting = adapter.default_setting(scenario)  # kinematic: Newton at each time, no step
    assert math.isnan(self_check.step_halving(adapter, scenario, setting, np.zeros(1), None))  # type: ignore[arg-type]


def test_solve_warns_when_half_the_step_moves_the_run(capsys, tmp_path) -> None:
    argv = ["solve", "andrews_squeezer", "--set", "spring_stiffness=1e6", "--engine", "mujoco"]
    assert main([*argv, "--setting", "dt=5e-5", "--out", str(tmp_path / "x.csv")]) == 0
    err = capsys.readouterr().err
    assert err.startswith("mbxval: warning: mujoco drifted:") and "at half the step" in err


def test_a_coarse_grid_does_not_make_an_exact_driven_run_look_drifted() -> None:
    """The four-bar's closed form with its Newton-Euler driving torque, on 20 outputs a turn: the
    trapezoidal work is 0.15 of the energy scale off there, which the quadrature's own uncertainty
    (the work over every other output) accounts for. What such a grid cannot resolve it cannot judge:
    a bias doing work of the whole energy scale over the run still shows."""
    from reports.scoring.truth import independent_truth

    scenario = dataclasses.replace(scenarios.build("four_bar"), steps=20)
    truth = independent_truth(scenario, np.asarray(scenario.times())).trajectory
    assert self_check.energy_change(scenario, truth) < self_check.ENERGY_LIMIT / 10
    scale = max(float(np.max(kinetic_energy(scenario, truth))), energy_scale(scenario, truth))
    bias = scale / (50.0 * scenario.t_end)
    extras = {**truth.extras, "crank_drive.force": truth.extras["crank_drive.force"] + bias}
    assert (
        self_check.energy_change(scenario, dataclasses.replace(truth, extras=extras))
        > self_check.ENERGY_LIMIT
    )


@pytest.mark.parametrize("steps", [1, 2, 3])
def test_a_grid_too_short_to_halve_cannot_judge_the_work_done(steps: int) -> None:
    """The four-bar's closed form (an exact run) on 2 to 4 grid times: the trapezoidal work over a
    whole turn in one to three intervals is off by up to the whole energy scale, and a grid under 5
    times cannot be halved to estimate that error, so the balance is not judged (NaN), never
    called a drift."""
    from reports.scoring.truth import independent_truth

    scenario = dataclasses.replace(scenarios.build("four_bar"), steps=steps)
    truth = independent_truth(scenario, np.asarray(scenario.times())).trajectory
    assert math.isnan(self_check.energy_change(scenario, truth))
    assert self_check.verdict(0.0, self_check.energy_change(scenario, truth)) == ""


def test_a_short_grid_of_a_conservative_run_is_still_judged() -> None:
    """Where no work is done (free dynamics under gravity alone) there is no quadrature to doubt: a
    doctored kinetic energy on 3 grid times still shows."""
    scenario = dataclasses.replace(scenarios.build("compound_pendulum"), t_end=0.5, steps=2)
    truth = simulate(scenario, np.asarray(scenario.times()), 1e-12).trajectory()
    assert self_check.energy_change(scenario, truth) < 1e-8
    assert truth.velocity is not None
    doctored = dataclasses.replace(truth, velocity=truth.velocity * np.array([1.0, 1.0, 1.2])[:, None, None])
    assert self_check.energy_change(scenario, doctored) > self_check.ENERGY_LIMIT


def test_solve_on_one_output_step_warns_of_no_drift(capsys, tmp_path) -> None:
    assert main(["solve", "four_bar", "--steps", "1", "--out", str(tmp_path / "x.csv")]) == 0
    assert "drifted" not in capsys.readouterr().err


def test_step_halving_is_half_a_first_order_run_s_error_at_the_run_s_own_times_and_step() -> None:
    """MuJoCo's Euler on the compound pendulum (a hinge chain, no soft constraint) is first order:
    its position error is C(t) dt to leading order, so the run at dt and the run at dt / 2 differ by
    C(t) dt / 2, half the run's own error against the native solver at 1e-12. Positions are measured
    whatever levels the scenario compares (velocity only here), on the grid asked for (not the
    scenario's own), at the setting's step (not the default's)."""
    from adapters.setting import Setting
    from reports.scoring.level_error import level_errors

    scenario = dataclasses.replace(
        scenarios.build("compound_pendulum"), t_end=0.5, steps=10, levels=("velocity",)
    )
    times = np.linspace(0.0, 0.4, 5)
    truth = simulate(scenario, times, 1e-12).trajectory()
    adapter = load_engine("mujoco")
    setting = Setting.of("Euler", **{**dict(adapter.default_setting(scenario).options), "dt": 1e-3})
    run = adapter.run(scenario, setting, times)
    assert run.status == "ok" and run.trajectory is not None, run.message
    error = level_errors(scenario, run.trajectory, truth, ("position",))["error_position"]
    assert error > 1e-3  # far above round-off and the truth's own error
    halving = self_check.step_halving(adapter, scenario, setting, times, run.trajectory)
    assert halving == pytest.approx(error / 2, rel=0.02)


def test_only_free_dynamics_can_keep_t_plus_v() -> None:
    """Drivers do work on a mechanism in the dynamic analysis too, and a kinematic analysis has no
    dynamics to conserve, drivers or not."""
    driven = dataclasses.replace(scenarios.build("four_bar"), analysis="dynamic")
    assert not driven.forces and not self_check.conservative(driven)
    still = dataclasses.replace(scenarios.build("compound_pendulum"), analysis="kinematic")
    assert not still.drivers and not self_check.conservative(still)


def test_a_figure_at_its_limit_is_no_drift_and_the_verdict_lists_every_drift_in_full() -> None:
    """A limit is the largest figure allowed ("above the limit" drifts); the verdict says each
    drift with its figure and limit, in order, separated by "; "."""
    at_limits = (self_check.RESIDUAL_LIMIT, self_check.ENERGY_LIMIT, self_check.STEP_LIMIT)
    assert self_check.verdict(*at_limits) == ""
    assert self_check.verdict(math.inf, math.nan) == "drifted: constraint residual not finite"
    assert self_check.verdict(2e-3, 0.5, 0.25) == (
        "drifted: constraint residual 0.002 (limit 0.001); energy T + V changed by 0.5 of its energy "
        "scale beyond the work done on it (limit 0.01); positions moved by 0.25 at half the step "
        "(limit 0.01)"
    )


def _four_bar_truth(steps: int) -> tuple[scenarios.Scenario, Trajectory]:
    """The four-bar's closed form with its Newton-Euler driving torque on `steps` intervals."""
    from reports.scoring.truth import independent_truth

    scenario = dataclasses.replace(scenarios.build("four_bar"), steps=steps)
    return scenario, independent_truth(scenario, np.asarray(scenario.times())).trajectory


def test_every_other_grid_time_keeps_every_level_and_extra() -> None:
    _, truth = _four_bar_truth(6)
    assert truth.velocity is not None and truth.acceleration is not None and truth.extras
    half = self_check._every_other(truth)
    assert half.bodies == truth.bodies and (half.times == truth.times[::2]).all()
    for level in ("position", "velocity", "acceleration"):
        assert (half.level(level) == truth.level(level)[::2]).all(), level
    assert half.extras.keys() == truth.extras.keys()
    assert all((half.extras[name] == values[::2]).all() for name, values in truth.extras.items())
    bare = self_check._every_other(dataclasses.replace(truth, acceleration=None))
    assert bare.acceleration is None and (bare.velocity == truth.velocity[::2]).all()


def test_the_quadrature_is_judged_from_five_grid_times_on() -> None:
    """Five times are the fewest whose every other one (three) still gives the work a quadrature
    with a middle point: there the uncertainty is the largest gap between the work over every other
    time and the work on the grid (on four times or fewer the balance is not judged at all:
    test_a_grid_too_short_to_halve_cannot_judge_the_work_done)."""
    from reports.scoring.work import work

    for steps in (2, 3):
        scenario, truth = _four_bar_truth(steps)
        assert math.isnan(self_check.energy_change(scenario, truth))
    scenario, truth = _four_bar_truth(4)
    done = work(scenario, truth)
    coarse = work(
        scenario,
        dataclasses.replace(
            truth,
            times=truth.times[::2],
            position=truth.position[::2],
            velocity=truth.velocity[::2],
            acceleration=truth.acceleration[::2],
            extras={name: values[::2] for name, values in truth.extras.items()},
        ),
    )
    assert done is not None and coarse is not None
    expected = float(np.max(np.abs(coarse - done[::2])))
    assert expected > 0.0
    assert self_check._quadrature_uncertainty(scenario, truth, done) == expected


def test_a_scene_at_rest_whose_height_changes_is_judged_against_the_energy_floor() -> None:
    """The compound pendulum held at its start pose, lifted by dy from the second grid time on: no
    kinetic energy, no work, T + V up by M g dy. The scale is the floor M L^2 / t_end^2
    (energy_drift.energy_scale), so the figure is M g dy t_end^2 / (M L^2)."""
    scenario = dataclasses.replace(scenarios.build("compound_pendulum"), t_end=0.5, steps=10)
    times = np.asarray(scenario.times())
    bodies = tuple(body.name for body in scenario.bodies)
    start = simulate(scenario, times[:2], 1e-12).trajectory().select(bodies).position
    assert start is not None
    pose = np.repeat(start[:1], times.size, axis=0)
    dy = 1e-4
    pose[1:, :, 1] += dy
    rest = np.zeros_like(pose)
    lifted = Trajectory(times, bodies, pose, rest, rest)
    mass = sum(body.mass for body in scenario.bodies)
    g = float(np.hypot(*scenario.gravity))
    expected = mass * g * dy * 0.5**2 / (mass * scenario.characteristic_length**2)
    assert self_check.energy_change(scenario, lifted) == pytest.approx(expected, rel=1e-9)


def test_a_bias_whose_work_dwarfs_the_motion_is_judged_against_that_work() -> None:
    """A driving-torque bias doing 100 times the four-bar's largest kinetic energy: the balance is
    off by about all the work done (a figure near 1), not by a hundred energy scales."""
    scenario, truth = _four_bar_truth(40)
    scale = float(np.max(kinetic_energy(scenario, truth)))
    angle = float(
        truth.position[-1, truth.bodies.index("crank"), 2] - truth.position[0, truth.bodies.index("crank"), 2]
    )
    bias = 100.0 * scale / abs(angle)
    extras = {**truth.extras, "crank_drive.force": truth.extras["crank_drive.force"] + bias}
    change = self_check.energy_change(scenario, dataclasses.replace(truth, extras=extras))
    assert 0.9 < change < 1.0


def test_a_run_without_velocities_or_of_point_masses_is_judged_as_far_as_it_can_be() -> None:
    """No velocities: no kinetic energy, no balance (NaN). Bodies with mass and no rotational
    inertia (point masses) still have one."""
    scenario, truth = _four_bar_truth(8)
    assert math.isnan(
        self_check.energy_change(scenario, dataclasses.replace(truth, velocity=None, acceleration=None))
    )
    points = dataclasses.replace(
        scenario, bodies=tuple(dataclasses.replace(body, inertia=0.0) for body in scenario.bodies)
    )
    assert all(body.mass > 0.0 for body in points.bodies)
    assert math.isfinite(self_check.energy_change(points, truth))
