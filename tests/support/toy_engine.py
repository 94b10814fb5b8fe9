"""A toy engine for the test that adds an engine (tests/test_adding_an_engine.py): the native solver
under another name, with its own colour, package and stress settings. A fake is fine there: what is
tested is that an engine's facts, declared on its adapter alone, reach every consumer."""

from __future__ import annotations

from adapters.base import Setting
from adapters.probes import STIFFNESS, Probe
from adapters.reference import ReferenceAdapter
from scenarios.scenario import Scenario

COLOUR = "#0a0b0c"
PACKAGE = "pytest"
"""A distribution installed wherever the tests run, so that its version is recorded."""
STIFF = Setting.of("newton", tolerance=1e-6)
"""The toy's extra setting for a stiffness probe."""


class ToyAdapter(ReferenceAdapter):
    """The native solver as engine `toy`."""

    name = "toy"
    colour = COLOUR
    packages = (PACKAGE,)

    def version(self) -> str:
        return "0.1-toy"

    def probe_settings(self, probe: Probe, scenario: Scenario) -> list[Setting] | None:
        return [self.default_setting(scenario), STIFF] if probe == STIFFNESS else None
