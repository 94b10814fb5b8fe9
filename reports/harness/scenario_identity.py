"""Which mechanism a stored row measured: a short digest of the scenario's canonical file text
(scenarios.identity.digest).

Results are keyed by the scenario's name, and a scenario file chooses its own `name`: two different
files (or one file edited between runs) can claim the same name. Every row records the digest of
the scenario it measured (`scenario_digest`), and a file whose name is already taken in a store by
a different mechanism, or by another file of the same run, is refused with a message saying so,
before anything runs: rows of two mechanisms never mix under one name. (A built-in family's rows
follow the revision instead: a resume reruns them when the code changes, reports.harness.resume.)
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from scenarios import ScenarioError, load
from scenarios.identity import digest
from scenarios.scenario import Scenario

__all__ = ["digest", "name_clash", "stored_clash", "stored_scenario"]


def stored_scenario(name: str) -> Scenario | None:
    """The scenario a stored row names (a family, a variant, a file, a swept point), rebuilt to read
    its constraints and masses; None where it no longer builds (renamed, or a file since edited)."""
    try:
        return load(name)
    except ScenarioError:
        return None


def name_clash(sources: Mapping[str, Scenario]) -> str | None:
    """Why two of these scenarios (by the name or path they were given) cannot be stored together:
    different mechanisms under one scenario name; None when there is no clash."""
    seen: dict[str, tuple[str, str]] = {}
    for given, scenario in sources.items():
        mine = digest(scenario)
        other = seen.setdefault(scenario.name, (given, mine))
        if other[1] != mine:
            return (
                f"{other[0]} and {given} both name their scenario '{scenario.name}' but describe "
                f"different mechanisms (digests {other[1]}, {mine}): give one of them another `name`"
            )
    return None


def stored_clash(rows: Iterable[Mapping[str, Any]], given: str, scenario: Scenario, store: str) -> str | None:
    """Why `scenario` (given as `given`) cannot join the rows of `store`: they hold a different
    mechanism under its name (another file, or this file before an edit); None otherwise."""
    mine = digest(scenario)
    theirs = sorted(
        {
            str(r.get("scenario_digest") or "")
            for r in rows
            if r.get("scenario") == scenario.name and r.get("scenario_digest")
        }
        - {mine}
    )
    if not theirs:
        return None
    return (
        f"{store} holds results of another mechanism named '{scenario.name}' (digest {theirs[0]}; "
        f"{given} is {mine}: another file of that name, or this file before an edit): give the file "
        "another `name` or use another --out"
    )
