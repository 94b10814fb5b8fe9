"""The wrong-branch classifier: a mirrored closure is a wrong branch, a small error is not, a
result off every closure has left the mechanism, and past a singular configuration the branch an
engine picked is named."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from reference_solver import solve
from reports.stress.branch_check import check_branch
from scenarios.trajectory import Trajectory


def positions(trajectory: Trajectory) -> np.ndarray:
    assert trajectory.position is not None
    return trajectory.position


@pytest.fixture(scope="module")
def four_bar() -> tuple[scenarios.Scenario, Trajectory, Trajectory]:
    """The open four-bar, its truth, and the crossed (mirrored) closure on the same grid."""
    scenario = scenarios.build("four_bar")
    truth = solve(scenario)
    crossed = solve(scenarios.build("four_bar/crossed"), scenario.times())
    return scenario, truth, crossed


def _with_positions(trajectory: Trajectory, position: np.ndarray) -> Trajectory:
    return dataclasses.replace(trajectory, position=position)


def test_a_mirrored_result_is_a_wrong_branch_from_the_start(four_bar) -> None:  # type: ignore[no-untyped-def]
    scenario, truth, crossed = four_bar
    check = check_branch(scenario, crossed, truth)
    first = check.first("other")
    assert first is not None and first.time == 0.0
    assert first.mirrored and first.distance < 1e-9 and first.separation > 0.5
    assert {p.kind for p in check.points} == {"other"}


def test_a_jump_to_the_mirrored_closure_is_found_where_it_happens(four_bar) -> None:  # type: ignore[no-untyped-def]
    scenario, truth, crossed = four_bar
    jump = 137
    position = truth.position.copy()
    position[jump:] = crossed.position[jump:]
    check = check_branch(scenario, _with_positions(truth, position), truth)
    first = check.first("other", "off")
    assert first is not None and first.kind == "other"
    assert first.time == pytest.approx(truth.times[jump])


def test_a_small_error_is_not_a_branch(four_bar) -> None:  # type: ignore[no-untyped-def]
    """Noise of 2e-3 of the characteristic length: every checked time is on the truth's closure."""
    scenario, truth, _ = four_bar
    noise = np.random.default_rng(7).standard_normal(truth.position.shape) * 1e-4
    check = check_branch(scenario, _with_positions(truth, truth.position + noise), truth)
    assert check.points and {p.kind for p in check.points} == {"same"}


def test_a_result_off_every_closure_has_left_the_mechanism(four_bar) -> None:  # type: ignore[no-untyped-def]
    scenario, truth, _ = four_bar
    shifted = truth.position.copy()
    shifted[:, :, 1] += 0.5 * scenario.characteristic_length  # every body half a crank up
    check = check_branch(scenario, _with_positions(truth, shifted), truth)
    assert check.first("other") is None
    assert check.first("off") is not None and check.first("off").time == 0.0  # type: ignore[union-attr]


def test_the_slider_on_the_other_side_of_the_crank_is_a_wrong_branch() -> None:
    """The slider-crank's other closure, built by hand: the rod mirrored about the vertical
    through A (th3 -> pi - th3), the slider at x_A - l3 cos th3."""
    scenario = scenarios.build("slider_crank")
    truth = solve(scenario)
    l2, l3 = (float(scenario.parameter(k)) for k in ("crank_length", "rod_length"))
    crank, rod, slider = (positions(truth)[:, k, :].copy() for k in range(3))
    th2, th3 = crank[:, 2], math.pi - rod[:, 2]
    ax, ay = l2 * np.cos(th2), l2 * np.sin(th2)
    rod = np.column_stack([ax + l3 / 2 * np.cos(th3), ay + l3 / 2 * np.sin(th3), th3])
    slider = np.column_stack([ax + l3 * np.cos(th3), slider[:, 1], slider[:, 2]])
    mirrored = _with_positions(truth, np.stack([crank, rod, slider], axis=1))
    first = check_branch(scenario, mirrored, truth).first("other")
    assert first is not None and first.time == 0.0 and first.mirrored


def _partial(truth: Trajectory, end: int) -> Trajectory:
    """The truth with no configuration from index `end` on (as past a singular configuration)."""
    position = positions(truth).copy()
    position[end:] = np.nan
    return _with_positions(truth, position)


def test_past_the_truths_end_the_picked_branch_is_named() -> None:
    """Through the change point: the crossed closure after it is the mirrored branch of the open
    one before it; the open closure after it keeps the branch."""
    scenario = scenarios.build("four_bar/stress_change_point")
    times = np.asarray(scenario.times())
    end = int(np.searchsorted(times, (math.pi - 0.3) / 50.0))
    open_branch = solve(scenario, times[:end])
    later = times[end:]

    def after(branch: int) -> Trajectory:
        """The closure of `branch` from times[end] on, assembled there (its own time starts at 0)."""
        start = {"theta0": 0.3 + 50.0 * later[0], "branch": branch}
        return solve(scenarios.build("four_bar/stress_change_point", overrides=start), later - later[0])

    crossed, again_open = after(-1), after(1)

    def joined(rest: Trajectory) -> Trajectory:
        position = np.concatenate([open_branch.position, rest.position])
        return Trajectory(times, open_branch.bodies, position=position)

    truth = _partial(joined(again_open), end)
    switched = check_branch(scenario, joined(crossed), truth)
    kept = check_branch(scenario, joined(again_open), truth)
    assert {p.kind for p in switched.points if p.time >= times[end]} == {"switched"}
    assert {p.kind for p in kept.points if p.time >= times[end]} == {"kept"}
