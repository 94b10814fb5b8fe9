"""A perf_counter that moves only when a call spends time on it, for timing tests: patched in for
the `time` module of adapters.timing and adapters.spent, every measured second is a known one."""

from __future__ import annotations

import pytest

from adapters import spent, timing


class Clock:
    """`perf_counter` reads `now`; `spend` moves it."""

    def __init__(self) -> None:
        self.now = 0.0

    def perf_counter(self) -> float:
        return self.now

    def spend(self, seconds: float) -> None:
        self.now += seconds


@pytest.fixture
def clock(monkeypatch: pytest.MonkeyPatch) -> Clock:
    """The fake clock, read by adapters.timing and adapters.spent for the test's length."""
    fake = Clock()
    monkeypatch.setattr(timing, "time", fake)
    monkeypatch.setattr(spent, "time", fake)
    return fake
