"""What a resumed run does with the rows it finds stored: keep them, or run them again, and why.

A stored row is run again when it is a failure that may pass now (`failed`, `timeout`: a busy
machine, a missing library) unless `keep_failures`; when it was made under another git revision or
another engine version (stale) unless `keep_stale`, which keeps it marked `stale`; and when it is
an engine's default-setting `ok` run whose trajectory the report draws but the store has lost.
A row is never dropped because its engine cannot be loaded now: those rows stay as they are.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from reports.store import NOT_RUN

if TYPE_CHECKING:
    from reports.store import Key, ResultsStore

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


class StoredRuns:
    """The rows a run finds in its store, indexed by scenario and engine (a sweep of many points
    reconciles each pair without reading every row), and what the resume decides about each."""

    def __init__(self, store: ResultsStore, revision: str, policy: ResumePolicy) -> None:
        self.store, self.revision, self.policy, self.log = store, revision, policy, ResumeLog()
        self.by_pair: defaultdict[tuple[str, str], list[Key]] = defaultdict(list)
        for key in store.rows:
            self.by_pair[key[:2]].append(key)

    def keeps(self, scenario: str, engine: str, version: str, setting: str) -> bool:
        """Whether the stored row of this run is kept (rerun_reason), counted in the log."""
        key = (scenario, engine, setting)
        row = self.store.rows.get(key)
        if row is None:
            return False
        reason = rerun_reason(row, self.revision, version, key in self.store.trajectories, self.policy)
        if reason is not None:
            self.log.reasons[reason] += 1
        stale = staleness(row, self.revision, version)
        if stale and reason in (STALE, None):
            self.log.stale_from[stale] += 1
        if reason is None and stale:
            self.log.kept_stale += 1
            row["stale"] = True
        return reason is None

    def keeps_unavailable(self, scenario: str, engine: str) -> bool:
        """Whether the store has rows of an engine that cannot be loaded now (counted in the log)."""
        count = sum(1 for k in self.by_pair[(scenario, engine)] if k[2] != NOT_RUN and k in self.store.rows)
        if count:
            self.log.kept_unavailable[engine] = self.log.kept_unavailable.get(engine, 0) + count
        return count > 0

    def reconcile(self, scenario: str, engine: str, planned: set[str] | None) -> None:
        """Make the stored rows of this scenario-engine pair agree with the plan (`planned` setting
        labels, None when the pair does not run): a pair that no longer runs keeps only its reason
        row; one that runs loses its old reason row; stored settings outside the plan (another
        suite's ladder) stay, but are no longer the default."""
        rows, trajectories = self.store.rows, self.store.trajectories
        for key in [k for k in self.by_pair.pop((scenario, engine), []) if k in rows]:
            if (planned is not None) == (key[2] == NOT_RUN):
                del rows[key]
                trajectories.pop(key, None)
            elif planned is not None and key[2] not in planned:
                rows[key]["is_default"] = False
                trajectories.pop(key, None)
