"""Work of a known length on the process's CPU clock, for fake engines whose timing a test checks:
the harness times CPU time (adapters.timing), on which a sleep costs nothing."""

from __future__ import annotations

import time


def work(seconds: float) -> None:
    """Spin until this process has spent `seconds` of CPU time (however long that takes on the
    wall clock of a busy machine)."""
    end = time.process_time() + seconds
    while time.process_time() < end:
        pass
