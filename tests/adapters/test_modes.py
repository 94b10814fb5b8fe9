"""Every engine declares what each of its modes measures; the runs and `mbxval list` carry it."""

from __future__ import annotations

import pytest

import adapters
from adapters.modes import ADAPTER, ENGINE, Mode, measures_of


def test_measures_names_who_computes_and_the_derived_levels() -> None:
    mode = Mode("m", ADAPTER, "Newton on rows", (("velocity", "adapter solve"),))
    assert (
        mode.measures
        == "adapter loop on the engine's kinematics: Newton on rows; derived: velocity (adapter solve)"
    )
    assert Mode("e", ENGINE, "its integrator").measures == "engine's own solver: its integrator"
    assert measures_of((mode,), "m") == mode.measures
    assert measures_of((mode,), "other") == ""


@pytest.mark.parametrize("name", adapters.names())
def test_every_default_and_ladder_mode_is_declared(name: str) -> None:
    from scenarios.registry import build

    adapter = adapters.load(name)
    declared = {mode.name for mode in adapter.measured}
    assert declared == set(adapter.modes)
    for scenario in ("slider_crank", "cam_roller"):
        built = build(scenario)
        if adapter.supports(built) is None:
            modes = {s.mode for s in [adapter.default_setting(built), *adapter.ladder(built)]}
            assert modes <= declared
