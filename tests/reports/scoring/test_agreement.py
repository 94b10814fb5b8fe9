"""The cross-engine pair matrix on the fake engine, whose offset from the fake truth is known."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import scenarios
from reports.scoring.agreement import pair_differences, widest
from reports.scoring.level_error import characteristic_rate
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
