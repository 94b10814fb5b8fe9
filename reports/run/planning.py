"""Planning a run: for each scenario and engine, the settings to run (a Group), or the row that
says why the engine does not run there (unavailable, unsupported, a broken adapter)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from adapters.base import Adapter, Setting
from reports.run.rows import failure_row
from scenarios import Scenario

NOT_INSTALLED = "not installed"
"""What the runner holds for an engine whose package is not installed here: it plans no row for it
(an optional engine's absence is said once, not as a failure per scenario)."""
SettingsHook = Callable[[Scenario, Adapter], list[Setting] | None]
"""A suite's own settings for a scenario and engine (the first is the default), or None: the engine's."""


@dataclass
class Group:
    """The planned runs of one engine on one scenario, or the row that says why there are none."""

    scenario: Scenario
    engine: str
    adapter: Adapter | None
    version: str
    jobs: list[tuple[Setting, bool]] = field(default_factory=list)
    reason_row: dict[str, Any] | None = None
    untuned: Setting | None = None
    """The engine's own defaults (Adapter.untuned_setting), run beside its ladder; None if it has none."""

    def is_untuned(self, setting: Setting) -> bool:
        return self.untuned is not None and setting == self.untuned


def plan_engine(
    scenario: Scenario, engine: str, adapter: Adapter | str, ladder: bool, settings: SettingsHook | None
) -> Group:
    """The group of `engine` on `scenario`; `adapter` is the loaded engine or why it cannot be loaded,
    `ladder` False plans only the default setting, `settings` is the suite's hook."""
    if adapter == NOT_INSTALLED:
        return Group(scenario, engine, None, NOT_INSTALLED)
    if isinstance(adapter, str):
        row = failure_row(scenario, engine, "unavailable", None, True, "failed", adapter)
        return Group(scenario, engine, None, "unavailable", reason_row=row)
    version = adapter._safe_version()
    group = Group(scenario, engine, adapter, version)
    try:
        reason = adapter.supports(scenario)
        if reason is not None:
            group.reason_row = failure_row(scenario, engine, version, None, True, "unsupported", reason)
            return group
        default = adapter.default_setting(scenario)
        planned = adapter.ladder(scenario) if ladder else []
        chosen = settings(scenario, adapter) if settings else None
        if chosen:
            default, planned = chosen[0], chosen
        elif ladder:
            group.untuned = adapter.untuned_setting(scenario)
            planned = [*planned, *([group.untuned] if group.untuned is not None else [])]
    except Exception as error:  # a broken adapter costs its own rows only
        message = f"cannot plan the runs: {type(error).__name__}: {error}"
        group.reason_row = failure_row(scenario, engine, version, None, True, "failed", message)
        return group
    group.jobs = [(s, s == default) for s in dict.fromkeys([*planned, default])]
    return group
