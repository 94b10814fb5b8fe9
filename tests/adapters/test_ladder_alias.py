"""`Adapter.sweep`, the old name of the settings ladder, keeps working for plug-in engines written
before the rename, with a DeprecationWarning: a subclass that defines `sweep` has it run as its
ladder, `super().sweep()` reaches the parent's ladder, and calling `sweep` on any adapter gives its
ladder. The runner plans over the ladder either way."""

from __future__ import annotations

import warnings

import pytest

import scenarios
from adapters.base import Adapter, Setting
from adapters.reference import ReferenceAdapter
from reports.run.planning import plan_engine

OLD_LADDER = [Setting.of("newton", tolerance=1e-3), Setting.of("newton", tolerance=1e-9)]
"""An old-style plug-in's settings, none of them in the reference's own ladder."""


def _old_style() -> type[Adapter]:
    """A plug-in as written before the rename: it defines `sweep`, not `ladder`."""

    class OldPlugin(ReferenceAdapter):
        name = "old_plugin"

        def sweep(self, scenario: scenarios.Scenario) -> list[Setting]:
            return list(OLD_LADDER)

    return OldPlugin


def test_a_plugin_defining_sweep_warns_once_at_its_definition_and_runs_it_as_its_ladder() -> None:
    with pytest.warns(DeprecationWarning, match="OldPlugin: Adapter.sweep is deprecated"):
        old = _old_style()
    scenario = scenarios.build("four_bar")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning per call: the definition warned already
        assert old().ladder(scenario) == OLD_LADDER
        group = plan_engine(scenario, "old_plugin", old(), True, None)
    assert [setting for setting, _ in group.jobs] == [
        *OLD_LADDER,
        ReferenceAdapter().default_setting(scenario),
    ]


def test_super_sweep_of_an_old_subclass_reaches_its_parents_ladder() -> None:
    with pytest.warns(DeprecationWarning):

        class Halved(ReferenceAdapter):
            def sweep(self, scenario: scenarios.Scenario) -> list[Setting]:
                return super().sweep(scenario)[::2]

    scenario = scenarios.build("slider_crank")
    with pytest.warns(DeprecationWarning, match="now `ladder"):
        halved = Halved().ladder(scenario)
    assert halved == ReferenceAdapter().ladder(scenario)[::2]
    assert len(halved) >= 2


def test_calling_sweep_on_a_renamed_adapter_warns_and_gives_its_ladder() -> None:
    adapter, scenario = ReferenceAdapter(), scenarios.build("four_bar")
    with pytest.warns(DeprecationWarning, match="Adapter.sweep is deprecated"):
        old_name = adapter.sweep(scenario)
    assert old_name == adapter.ladder(scenario)
    assert len(old_name) > 1  # the reference's tolerances, not the base's default alone


def test_an_adapter_defining_ladder_raises_no_warning() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")

        class New(ReferenceAdapter):
            def ladder(self, scenario: scenarios.Scenario) -> list[Setting]:
                return list(OLD_LADDER)

        assert New().ladder(scenarios.build("four_bar")) == OLD_LADDER
