"""The cross-engine pair matrix on the fake engine, whose offset from the fake truth is known."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import scenarios
from reports.scoring.agreement import pair_differences, widest
from reports.scoring.level_error import characteristic_rate
from scenarios.trajectory import Trajectory
from tests.support.fake_engine import GOOD, FakeAdapter, fake_truth


def test_pairs_of_fake_runs_differ_by_their_known_offsets(tmp_path: Path) -> None:
    scenario = scenarios.build("slider_crank")
    times = np.asarray(scenario.times())
    adapter = FakeAdapter(tmp_path / "log")
    coarse, fine = (adapter.run(scenario, s, times).trajectory for s in GOOD)  # x off by dt
    assert coarse is not None and fine is not None
    runs = {"coarse": coarse, "fine": fine, "exact": fake_truth(scenario, times)}
    length, rate = scenario.characteristic_length, characteristic_rate(scenario)
    pairs = pair_differences(runs, length, rate)
    assert set(pairs) == {("coarse", "exact"), ("coarse", "fine"), ("exact", "fine")}
    assert pairs[("coarse", "exact")]["position"] == pytest.approx(GOOD[0]["dt"] / length)
    assert pairs[("exact", "fine")]["position"] == pytest.approx(GOOD[1]["dt"] / length)
    assert pairs[("coarse", "fine")]["position"] == pytest.approx((GOOD[0]["dt"] - GOOD[1]["dt"]) / length)
    assert pairs[("coarse", "fine")]["velocity"] == 0.0
    assert math.isnan(pairs[("coarse", "exact")]["acceleration"])  # the fake gives no accelerations
    assert widest(pairs, "position") == (("coarse", "exact"), pytest.approx(GOOD[0]["dt"] / length))
    assert widest(pairs, "acceleration") == (None, pytest.approx(math.nan, nan_ok=True))


def _at_rest(times: np.ndarray, bodies: tuple[str, ...], x: float) -> Trajectory:
    """Every body at (x, 0, 0) and at rest on `times`."""
    shape = (len(times), len(bodies), 3)
    position = np.zeros(shape)
    position[:, :, 0] = x
    return Trajectory(times, bodies, position, np.zeros(shape), np.zeros(shape))


def test_runs_on_grids_of_different_lengths_do_not_compare_and_a_body_one_lacks_is_left_out() -> None:
    """Pairs are compared over the bodies both carry: 'extra', carried by one run only, does not
    enter (its offset of 9 would). A pair on grids of 5 and 6 times has no difference at any level
    (NaN), the runs not being at the same times."""
    five, six = np.linspace(0.0, 1.0, 5), np.linspace(0.0, 1.0, 6)
    runs = {
        "a": _at_rest(five, ("crank", "extra"), 0.0),
        "b": _at_rest(five, ("crank",), 0.5),
        "c": _at_rest(six, ("crank",), 0.5),
    }
    runs["a"].position[:, 1, 0] = 9.0
    pairs = pair_differences(runs, length=2.0, rate=1.0)
    assert pairs[("a", "b")] == {"position": 0.25, "velocity": 0.0, "acceleration": 0.0}
    for pair in (("a", "c"), ("b", "c")):
        assert all(math.isnan(value) for value in pairs[pair].values()), pair
