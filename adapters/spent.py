"""What a run spent before it failed: its phases marked as they end (the build, each untimed warm-up
call), never inside a timed call, so that a run that raises is charged the seconds it took, split
into build, warm-up and timed repeats as an ok run's are (its `run_time`, a minimum of repeats,
stays empty: a failed run has no time of its own to show)."""

from __future__ import annotations

import time
from dataclasses import dataclass, field


@dataclass
class Stopwatch:
    """Started with the run's build; `built` and `warmed` mark the ends of the build and of each
    warm-up call, `spent` splits the seconds up to now."""

    start: float = field(default_factory=lambda: time.perf_counter())
    built_at: float | None = None
    warmed_at: float | None = None
    warmups: int = 0

    def built(self) -> None:
        self.built_at = time.perf_counter()

    def warmed(self) -> None:
        self.warmed_at, self.warmups = time.perf_counter(), self.warmups + 1

    def spent(self, warmup: int) -> tuple[float, float, float]:
        """Seconds of the build, the warm-up and the timed repeats up to now, `warmup` being the
        warm-up calls the run was to make: a failure in the build is all build; one before the last
        warm-up call ended, warm-up; one after it (or with no warm-up), in the timed repeats."""
        now = time.perf_counter()
        if self.built_at is None:
            return now - self.start, 0.0, 0.0
        build = self.built_at - self.start
        if self.warmups < warmup:
            return build, now - self.built_at, 0.0
        timed_from = self.built_at if self.warmed_at is None else self.warmed_at
        return build, timed_from - self.built_at, now - timed_from
