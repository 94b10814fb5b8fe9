"""Every engine declares what each of its modes measures; the runs and `mbxval list` carry it."""

from __future__ import annotations

import pytest

import adapters
from adapters.base import Adapter
from adapters.modes import ADAPTER, ENGINE, Mode, measures_of
from tests.support.engines import ENGINES


def test_measures_names_who_computes_and_the_derived_levels() -> None:
    mode = Mode("m", ADAPTER, "Newton on rows", (("velocity", "adapter solve"),))
    assert (
        mode.measures
        == "adapter loop on the engine's kinematics: Newton on rows; derived: velocity (adapter solve)"
    )
    assert Mode("e", ENGINE, "its integrator").measures == "engine's own solver: its integrator"
    assert measures_of((mode,), "m") == mode.measures
    assert measures_of((mode,), "other") == ""


@pytest.mark.parametrize("name", ENGINES)
def test_every_default_and_ladder_mode_is_declared(name: str) -> None:
    from scenarios.registry import build

    adapter = adapters.load(name)
    declared = {mode.name for mode in adapter.measured}
    for scenario in ("slider_crank", "cam_roller"):
        built = build(scenario)
        if adapter.supports(built) is None:
            modes = {s.mode for s in [adapter.default_setting(built), *adapter.ladder(built)]}
            assert modes <= declared


@pytest.mark.parametrize("name", ENGINES)
def test_modes_are_the_names_of_measured_in_its_order(name: str) -> None:
    """One declaration: `modes` (what settings are checked against, and the unknown-mode message)
    lists the declared modes in the order `mbxval list` shows them."""
    adapter = adapters.load(name)
    assert adapter.modes == tuple(mode.name for mode in adapter.measured)
    assert adapter.modes[0] == adapter.measured[0].name


def test_an_engine_declaring_measured_alone_gets_its_modes_and_one_declaring_modes_keeps_them() -> None:
    class Measured(Adapter):
        measured = (Mode("b", ENGINE, "second letter"), Mode("a", ENGINE, "first letter"))

    class Listed(Adapter):  # as the README's minimal engine: modes without what they measure
        modes = ("exact",)

    class Inherited(Measured):
        pass

    assert Measured.modes == ("b", "a")
    assert Inherited.modes == ("b", "a")
    assert Listed.modes == ("exact",) and Listed.measured == ()


def test_exudyn_has_solver_parameters_for_each_declared_mode() -> None:
    from adapters.exudyn.adapter import MODES, ExudynAdapter

    assert set(MODES) == set(ExudynAdapter.modes)
