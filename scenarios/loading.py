"""One way to name a scenario everywhere: a built-in name (`family` or `family/variant`) or the
path of a scenario file (`*.toml`)."""

from __future__ import annotations

from collections.abc import Mapping

from scenarios.files import read_scenario
from scenarios.registry import build
from scenarios.scenario import Scenario


def is_scenario_file(name: str) -> bool:
    """Whether `name` names a scenario file rather than a built-in scenario."""
    return name.endswith(".toml")


def load(name_or_path: str, overrides: Mapping[str, str] | None = None) -> Scenario:
    """The scenario a name or a file describes. `overrides` set family parameters by name, or a
    file's values by dotted key path (`bodies.crank.mass`)."""
    if is_scenario_file(name_or_path):
        return read_scenario(name_or_path, overrides)
    return build(name_or_path, overrides=overrides)
