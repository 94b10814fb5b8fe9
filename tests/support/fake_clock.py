"""A process CPU clock and a wall clock that move only when a call spends time on them, for timing
tests: patched in for the `time` module of adapters.timing (which adapters.spent reads too), every
measured second is a known one. `spend` is work (both clocks move), `wait` is time the process
spends off the CPU (the wall clock alone moves: a sleep, or a machine busy with other jobs)."""

from __future__ import annotations

import pytest

from adapters import timing


class Clock:
    """`process_time` reads `cpu`, `perf_counter` reads `now`; `spend` moves both, `wait` the wall."""

    def __init__(self) -> None:
        self.now = 0.0
        self.cpu = 0.0

    def perf_counter(self) -> float:
        return self.now

    def process_time(self) -> float:
        return self.cpu

    def spend(self, seconds: float) -> None:
        self.now += seconds
        self.cpu += seconds

    def wait(self, seconds: float) -> None:
        self.now += seconds


@pytest.fixture
def clock(monkeypatch: pytest.MonkeyPatch) -> Clock:
    """The fake clocks, read by adapters.timing and adapters.spent for the test's length."""
    fake = Clock()
    monkeypatch.setattr(timing, "time", fake)
    return fake
