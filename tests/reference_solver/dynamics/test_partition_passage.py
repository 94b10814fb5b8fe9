"""The partitioned method at IFToMM A02's singular passages: C_q losing rank, where no choice of
independent coordinates stays regular. Where it cannot cross one it says which passage, when, and
what to use (ALI3-P), instead of "the dependent coordinates did not converge".

A02's two loops over 10 s pass the horizontal position ten times (the one-degree-of-freedom
equation's passage times, scenarios.families.n_four_bar_reference). Each repartition next to a
passage restarts the integrator a tenth nearer the singular instant (C_q's smallest singular values
4e-2, 4e-3, ..., 4e-6), and Newton on the dependent coordinates, singular there to round-off, gives
up: at t = 5.12031, 7e-3 s after the sixth passage, on the compiled path."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.dynamics import forward, simulate
from reference_solver.dynamics.partition import Partitioned
from reference_solver.dynamics.partition_passage import is_passage, rank_margin
from reference_solver.errors import ConvergenceError, SingularConfigurationError
from reference_solver.system import ConstraintSystem
from scenarios.families.n_four_bar_reference import reduced


def _a02(t_end: float) -> scenarios.Scenario:
    return scenarios.build("n_four_bar", overrides={"t_end": t_end, "steps": int(16 * t_end)})


def test_two_loops_over_ten_seconds_stop_at_the_sixth_passage_naming_it() -> None:
    scenario = _a02(10.0)
    passages = reduced(scenario).passages
    assert len(passages) == 10
    with pytest.raises(SingularConfigurationError) as caught:
        simulate(scenario, compiled=True)
    assert abs(caught.value.time - passages[5]) < 0.01, caught.value.time
    assert "singular passage at t=" in str(caught.value) and "use --mode ali3p" in str(caught.value)
    assert caught.value.rank_deficiency == 2  # both loops line up at once


def test_the_default_horizon_still_crosses_its_four_passages_on_the_parallelogram_branch() -> None:
    """Four seconds (the dynamics suite's scene): the partitioned method steps over each passage."""
    scenario = _a02(4.0)
    assert len(reduced(scenario).passages) == 4
    analysis = simulate(scenario, compiled=True)
    theta = analysis.q[:, 2::3]
    rockers = [k for k, b in enumerate(analysis.layout.bodies) if b.startswith("rocker")]
    assert np.max(np.abs(theta[:, rockers] - theta[:, [0]])) < 1e-10
    crank = reduced(scenario).angle(analysis.times)[0]
    assert np.max(np.abs(theta[:, 0] - crank)) < 1e-6  # the one-degree-of-freedom motion


def test_a_passage_that_cannot_be_crossed_is_named_with_its_time_and_the_method_that_crosses(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Newton made to fail wherever C_q is within 1e-3 of losing rank (as it does at the singular
    instant): the run stops at the first passage (t = 0.714) saying so, not with a bare
    'did not converge'."""
    made = forward.partitioned_ode

    def failing(system: ConstraintSystem, *args: object) -> Partitioned:
        ode = made(system, *args)  # type: ignore[arg-type]
        rates = ode.rates

        def near_singular(t: float, y: np.ndarray) -> np.ndarray:
            out = rates(t, y)
            if rank_margin(system, ode.jac if ode.jac.any() else system.jacobian(ode.q, t))[0] < 1e-3:
                raise ConvergenceError(f"did not converge at t={t:.6g}", time=t)
            return out

        ode.rates = near_singular  # type: ignore[method-assign]
        return ode

    monkeypatch.setattr(forward, "partitioned_ode", failing)
    with pytest.raises(SingularConfigurationError) as caught:
        simulate(_a02(1.0), compiled=False)
    first = reduced(_a02(1.0)).passages[0]
    assert abs(caught.value.time - first) < 0.01, caught.value.time
    assert "singular passage at t=" in str(caught.value) and "use --mode ali3p" in str(caught.value)
    assert caught.value.rank_deficiency == 2  # both loops line up at once


def test_a_repartition_shows_a_passage_only_when_it_regains_little() -> None:
    assert is_passage(0.02, 0.1) and not is_passage(0.05, 0.1) and not is_passage(0.5, 0.0)


def test_the_rank_margin_counts_the_ranks_a02_loses_at_the_horizontal_position() -> None:
    """At theta = 0 every loop lines up: two loops, two singular values of C_q at zero."""
    from reference_solver.system import ConstraintSystem as Plain

    scenario = scenarios.build("n_four_bar", overrides={"theta0": 1e-9})
    system = Plain(scenario)
    q = system.layout.initial_guess(scenario)
    margin, ranks = rank_margin(system, system.jacobian(q, 0.0))
    assert margin < 1e-8 and ranks == 2
    upright = scenarios.build("n_four_bar")
    q = system.layout.initial_guess(upright)
    assert rank_margin(system, system.jacobian(q, 0.0))[0] > 0.1
