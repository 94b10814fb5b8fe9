"""The repeat-noise benchmark replays the harness's own stopping rule on recorded repeat times: the
minimum and the seconds it reports are those `timed` gives on a clock that spends the same times."""

from __future__ import annotations

import pytest

from adapters import timing
from adapters.timing import enough, timed
from benchmarks.repeat_noise import by_the_rule
from reports.run.group_runs import AGREE, LONG_RUN, REPEATS_BUDGET
from tests.support.fake_clock import Clock

CASES = [
    [0.050, 0.0508, 0.5, 0.1],  # agree at the second: 2 repeats
    [0.050, 0.065, 0.045, 0.1],  # never agree: 3
    [0.050, 0.065, 0.06525, 0.1],  # the third agrees with the second, not the best: 3 anyway
    [0.300, 0.100, 0.100],  # over LONG_RUN: 1
    [0.070, 0.080, 0.0690, 0.1],  # the third agrees with the best: 3
    [0.100, 0.130, 0.090, 0.1],  # a third as long as the best would pass REPEATS_BUDGET: 2
    [0.200, 0.100, 0.100],  # a second would pass it: 1
]


@pytest.mark.parametrize("each", CASES)
def test_the_replayed_rule_is_timed_s(each: list[float], monkeypatch: pytest.MonkeyPatch) -> None:
    clock = Clock()
    monkeypatch.setattr(timing, "time", clock)
    left = iter(each)

    def action() -> None:
        clock.spend(next(left))

    found = timed(action, repeats=3, once_above=LONG_RUN, agree=AGREE, budget=REPEATS_BUDGET)
    best, spent = by_the_rule(each)
    assert best == pytest.approx(found.best, rel=1e-12)
    assert spent == pytest.approx(found.repeats_time, rel=1e-12)


def test_enough_stops_on_agreement_or_a_long_best_only() -> None:
    assert not enough(0.1, float("inf"), LONG_RUN, AGREE)  # a first repeat never agrees
    assert enough(0.3, float("inf"), LONG_RUN, AGREE)  # ... but may be long
    assert enough(0.1019, 0.100, LONG_RUN, 0.02) and not enough(0.103, 0.100, LONG_RUN, 0.02)
    assert not enough(0.100, 0.100, LONG_RUN, 0.0)  # agree 0: never
