"""IFToMM A02's criterion: the one-degree-of-freedom reference it is judged against, checked by its
own first integral, and B0's figures read from a run's crank."""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios
from reference_solver.dynamics import simulate
from scenarios.families.n_four_bar_reference import HIGH_PRECISION, b0_of, criterion, reduced


def test_the_reduced_motion_keeps_its_energy_and_starts_as_the_specification_says() -> None:
    """I theta'^2 / 2 + c sin theta is constant (c / I = g ((N + 1)/2 + N) / ((N + 1)/3 + N) per unit
    length); B0 starts at the crank's tip straight up, moving at 1 m/s along x."""
    scenario = scenarios.build("n_four_bar", overrides={"t_end": 10.0})
    found = reduced(scenario)
    ratio = 9.81 * (3 / 2 + 2) / (3 / 3 + 2)
    times = np.linspace(0.0, 10.0, 1001)
    theta, rate = found.angle(times)
    first = 0.5 * rate**2 + ratio * np.sin(theta)
    assert np.max(np.abs(first - first[0])) < 1e-10
    np.testing.assert_allclose(found.b0(np.array([0.0]))[0], [0.0, 1.0, 1.0, 0.0], atol=1e-15)
    # at each passage theta is a multiple of pi and |theta'| = sqrt(1 + 2 c / I)
    assert len(found.passages) == 10
    _, at = found.angle(found.passages)
    np.testing.assert_allclose(np.abs(at), math.sqrt(1 + 2 * ratio), rtol=1e-10)


def test_b0_is_the_crank_s_tip_from_its_frame() -> None:
    scenario = scenarios.build("n_four_bar", overrides={"t_end": 0.5, "steps": 5})
    trajectory = simulate(scenario).trajectory()
    b0 = b0_of(trajectory, 1.0)
    crank = trajectory.bodies.index("crank")
    # the crank's pivot is fixed at the origin, so B0 = 2 x its midpoint, velocity likewise
    np.testing.assert_allclose(b0[:, :2], 2 * trajectory.position[:, crank, :2], atol=1e-12)  # type: ignore[index]
    np.testing.assert_allclose(b0[:, 2:], 2 * trajectory.velocity[:, crank, :2], atol=1e-12)  # type: ignore[index]


def test_the_criterion_separates_a_fine_run_from_a_coarse_one() -> None:
    scenario = scenarios.build("n_four_bar", overrides={"t_end": 10.0, "steps": 400})
    fine = criterion(scenario, simulate(scenario, method="ali3p", step=4e-4, compiled=True).trajectory())
    coarse = criterion(scenario, simulate(scenario, method="ali3p", step=1.5e-3, compiled=True).trajectory())
    assert fine["benchmark_error"] < HIGH_PRECISION < coarse["benchmark_error"]
    assert fine["benchmark_limit"] == HIGH_PRECISION
    assert fine["invariant_error"] < 1e-10


def test_the_criterion_needs_every_rocker() -> None:
    scenario = scenarios.build("n_four_bar", overrides={"t_end": 0.1, "steps": 2})
    trajectory = simulate(scenario).trajectory()
    with pytest.raises(ValueError, match="every rocker"):
        criterion(scenario, trajectory.select(("crank", "coupler_1")))


@pytest.mark.slow
def test_a02_as_specified_meets_its_high_precision_criterion_on_the_default_path() -> None:
    """`mbxval solve n_four_bar/spec` on its default (ALI3-P at the rule's step), at the
    specification's 400 outputs: B0 to well within 1e-3."""
    import adapters

    scenario = scenarios.build("n_four_bar/spec", overrides={"steps": 400})
    result = adapters.load("reference").run(scenario)
    assert result.status == "ok" and result.trajectory is not None, result.message
    figures = criterion(scenario, result.trajectory)
    assert figures["benchmark_error"] < HIGH_PRECISION / 10 and figures["invariant_error"] < 1e-10
