"""The baselines that ship with the package (reports/baselines/*.json, package data), so that
`mbxval check --baseline default` works in any installation: a baseline is named by a shipped
name or given as a file path."""

from __future__ import annotations

from pathlib import Path

SHIPPED = Path(__file__).resolve().parent.parent / "baselines"
"""reports/baselines: `default.json` (the quick suite) and `dynamics.json` (the dynamics suite)."""


def names() -> list[str]:
    """The shipped baselines' names."""
    return sorted(p.stem for p in SHIPPED.glob("*.json"))


def resolve(given: str) -> Path:
    """The baseline file `given` names: a path as given, or a shipped baseline by name (a path
    that exists wins over a name)."""
    path = Path(given)
    if not path.exists() and given in names():
        return SHIPPED / f"{given}.json"
    return path
