"""What a run spent before it failed: its phases marked as they end (the build, each untimed warm-up
call), never inside a timed call, so that a run that raises is charged the seconds it took, split
into build, warm-up and timed repeats as an ok run's are (its `run_time`, a minimum of repeats,
stays empty: a failed run has no time of its own to show). CPU seconds, as adapters.timing measures,
with the wall clock's beside them (`spent_wall`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from adapters.timing import Instant, now


@dataclass
class Stopwatch:
    """Started with the run's build; `built` and `warmed` mark the ends of the build and of each
    warm-up call, `spent` splits the seconds up to now."""

    start: Instant = field(default_factory=now)
    built_at: Instant | None = None
    warmed_at: Instant | None = None
    warmups: int = 0

    def built(self) -> None:
        self.built_at = now()

    def warmed(self) -> None:
        self.warmed_at, self.warmups = now(), self.warmups + 1

    def spent(self, warmup: int) -> tuple[float, float, float]:
        """CPU seconds of the build, the warm-up and the timed repeats up to now, `warmup` being the
        warm-up calls the run was to make: a failure in the build is all build; one before the last
        warm-up call ended, warm-up; one after it (or with no warm-up), in the timed repeats."""
        return self._split(warmup, lambda instant: instant.cpu)

    def spent_wall(self, warmup: int) -> tuple[float, float, float]:
        """The same split as `spent`, in wall seconds."""
        return self._split(warmup, lambda instant: instant.wall)

    def _split(self, warmup: int, clock: Callable[[Instant], float]) -> tuple[float, float, float]:
        current, start = clock(now()), clock(self.start)
        if self.built_at is None:
            return current - start, 0.0, 0.0
        built = clock(self.built_at)
        if self.warmups < warmup:
            return built - start, current - built, 0.0
        timed_from = built if self.warmed_at is None else clock(self.warmed_at)
        return built - start, timed_from - built, current - timed_from
