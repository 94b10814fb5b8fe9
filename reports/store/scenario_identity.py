"""Which mechanism a stored row measured: a short digest of the scenario's canonical file text
(scenarios.identity.digest).

Rows are found by the scenario's name, and a name does not make a mechanism: a scenario file chooses
its own `name` (it may take a family's, `slider_crank`), and one file may be edited between runs.
Every row records the digest of the scenario it measured (`scenario_digest`), and one rule keeps two
mechanisms from sharing a name, whichever came first: a scenario (a family, a variant, a swept
point or a file) whose name the store holds rows of under another digest is refused before anything
runs (`stored_clash`: run, compare --out), as are two of one run (`name_clash`), and a store that
holds two digests under one name is refused by what reads it (`mixed_names`: report).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from scenarios import ScenarioError, load
from scenarios.identity import digest
from scenarios.scenario import Scenario

__all__ = ["digest", "mixed_names", "name_clash", "stored_clash", "stored_scenario"]


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


def _stored_digests(rows: Iterable[Mapping[str, Any]], name: str) -> set[str]:
    """The digests the rows stored under scenario `name` record (rows older than the column: none)."""
    return {str(r.get("scenario_digest") or "") for r in rows if r.get("scenario") == name} - {""}


def stored_clash(rows: Iterable[Mapping[str, Any]], given: str, scenario: Scenario, store: str) -> str | None:
    """Why `scenario` (given as `given`) cannot join the rows of `store`: they hold a different
    mechanism under its name (a family's rows and a file of its name, in either order, or a file
    before an edit); None otherwise."""
    mine = digest(scenario)
    theirs = sorted(_stored_digests(rows, scenario.name) - {mine})
    if not theirs:
        return None
    return (
        f"{store} holds results of another mechanism named '{scenario.name}' (digest {theirs[0]}; "
        f"{given} is {mine}): rows of two mechanisms never share a name; use another --out, or give "
        "a scenario file another `name`"
    )


def mixed_names(rows: Iterable[Mapping[str, Any]], store: str) -> str | None:
    """Why the rows of `store` cannot be shown: they hold two mechanisms under one scenario name
    (a store written before the rule above held, or edited); None otherwise."""
    by_name: dict[str, set[str]] = {}
    for row in rows:
        if row.get("scenario_digest"):
            by_name.setdefault(str(row.get("scenario")), set()).add(str(row["scenario_digest"]))
    name, digests = next(((n, d) for n, d in sorted(by_name.items()) if len(d) > 1), ("", set()))
    if not digests:
        return None
    return (
        f"{store} holds rows of more than one mechanism named '{name}' (digests "
        f"{', '.join(sorted(digests))}): a report would show them as one; rerun one of them into "
        "another directory"
    )
