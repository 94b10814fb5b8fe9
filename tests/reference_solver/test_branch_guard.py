"""The native solver never leaves its assembly branch in silence: a step whose converged
configuration is far from its predictor is retaken in halved steps (analysis.jumped)."""

from __future__ import annotations

import numpy as np
import pytest

import reference_solver.analysis as analysis
import scenarios
from reference_solver.compiled import path

UNDERCUT = "cam_roller/stress_undercut"  # the contact point sweeps a concave valley in a few steps


def test_coarse_grid_follows_the_branch_a_fine_grid_follows() -> None:
    scenario = scenarios.build(UNDERCUT)
    grid, fine = np.asarray(scenario.times()), np.asarray(scenario.times(steps=4 * scenario.steps))
    reference = analysis.analyse(scenario, fine, compiled=False).q[::4]
    for compiled in (True, False):
        np.testing.assert_allclose(
            analysis.analyse(scenario, grid, compiled=compiled).q, reference, rtol=0, atol=1e-12
        )


def test_without_the_guard_the_same_grid_jumps(monkeypatch: pytest.MonkeyPatch) -> None:
    """The guard is what keeps the branch: with it off, the step jumps and a false singularity follows."""
    scenario = scenarios.build(UNDERCUT)
    monkeypatch.setattr(analysis, "JUMP_FRACTION", 1e9)
    with pytest.raises(analysis.SingularConfigurationError):
        analysis.analyse(scenario, compiled=False)


def test_the_kernel_hands_a_jump_to_the_plain_path() -> None:
    scenario = scenarios.build(UNDERCUT)
    assert (
        path.run(scenario, np.asarray(scenario.times())).event == "a step left its branch (analysis.jumped)"
    )


def test_the_guard_stays_quiet_on_regular_coarse_grids() -> None:
    """Eight steps per revolution: every catalogue scenario runs in the kernel without a handover."""
    for name in scenarios.catalogue():
        scenario = scenarios.build(name)
        assert path.run(scenario, np.asarray(scenario.times(steps=8))).event == "ok", name
