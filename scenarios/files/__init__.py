"""Scenario files: mechanisms described in TOML (format 1, see docs/scenario-files.md)."""

from scenarios.files.reader import ScenarioFileError, parse_scenario, read_scenario
from scenarios.files.writer import scenario_toml

__all__ = ["ScenarioFileError", "parse_scenario", "read_scenario", "scenario_toml"]
