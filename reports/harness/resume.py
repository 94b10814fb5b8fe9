"""What a resumed run does with the rows it finds stored: keep them, or run them again, and why.

A stored row is run again when it is a failure that may pass now (`failed`, `timeout`: a busy
machine, a missing library) unless `keep_failures`; when it was made under another git revision or
another engine version (stale) unless `keep_stale`, which keeps it marked `stale`; and when it is
an engine's default-setting `ok` run whose trajectory the report draws but the store has lost.
A row is never dropped because its engine cannot be loaded now: those rows stay as they are.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

RETRIED = ("failed", "timeout")
RETRY, STALE, NO_TRAJECTORY, RERUN = "retry", "stale", "trajectory missing", "rerun"


@dataclass(frozen=True)
class ResumePolicy:
    rerun: bool = False  # run everything again
    keep_failures: bool = False
    keep_stale: bool = False


def staleness(row: Mapping[str, Any], revision: str, version: str) -> str:
    """Why the row is stale (made under another revision or engine version), or ''."""
    made = str(row.get("revision") or "") or "unknown"
    reasons = []
    if made != revision:
        reasons.append(f"revision {made}")
    if str(row.get("engine_version")) != version:
        reasons.append(f"{row.get('engine')} {row.get('engine_version')}")
    return " and ".join(reasons)


def rerun_reason(
    row: Mapping[str, Any], revision: str, version: str, has_trajectory: bool, policy: ResumePolicy
) -> str | None:
    """Why this stored row must be made again, or None to keep it."""
    if policy.rerun:
        return RERUN
    if row.get("status") in RETRIED and not policy.keep_failures:
        return RETRY
    if staleness(row, revision, version) and not policy.keep_stale:
        return STALE
    if bool(row.get("is_default")) and row.get("status") == "ok" and not has_trajectory:
        return NO_TRAJECTORY
    return None


@dataclass
class ResumeLog:
    """What the resume decided, summed up for the user in a few lines."""

    reasons: Counter[str] = field(default_factory=Counter)
    stale_from: Counter[str] = field(default_factory=Counter)
    kept_stale: int = 0
    kept_unavailable: dict[str, int] = field(default_factory=dict)

    def lines(self) -> list[str]:
        out = []
        if self.reasons[RETRY]:
            out.append(
                f"retrying {self.reasons[RETRY]} stored failed/timeout rows (--keep-failures keeps them)"
            )
        if self.reasons[STALE]:
            what = ", ".join(f"{n} from {w}" for w, n in sorted(self.stale_from.items()))
            out.append(
                f"rerunning {self.reasons[STALE]} stale rows ({what}; --keep-stale keeps them, marked)"
            )
        if self.kept_stale:
            what = ", ".join(f"{n} from {w}" for w, n in sorted(self.stale_from.items()))
            out.append(f"keeping {self.kept_stale} stale rows, marked stale ({what})")
        if self.reasons[NO_TRAJECTORY]:
            out.append(f"rebuilding {self.reasons[NO_TRAJECTORY]} missing trajectories")
        for engine, count in sorted(self.kept_unavailable.items()):
            out.append(f"{engine} is unavailable: its {count} stored rows are kept as they are")
        return out
