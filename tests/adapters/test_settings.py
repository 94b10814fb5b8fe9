"""Every engine's settings are checked where they enter: modes, option names, types and ranges."""

from __future__ import annotations

import math

import pytest

import adapters
import scenarios
from adapters.base import Setting, SettingError
from tests.support.engines import COMPARED, ENGINES


@pytest.mark.parametrize("engine", ENGINES)
def test_defaults_and_ladders_pass_their_own_declarations(engine: str) -> None:
    adapter = adapters.load(engine)
    for name in ("slider_crank", "spur_gears", "cam_roller"):
        scenario = scenarios.build(name)
        for setting in [adapter.default_setting(scenario), *adapter.ladder(scenario)]:
            assert adapter.check_setting(setting).mode == setting.mode


@pytest.mark.parametrize("engine", ENGINES)
def test_unknown_mode_and_option_name_the_known_ones(engine: str) -> None:
    adapter = adapters.load(engine)
    default = adapter.default_setting(scenarios.build("slider_crank"))
    with pytest.raises(SettingError, match="unknown mode 'nosuch'; known: " + ", ".join(adapter.modes)):
        adapter.check_setting(Setting("nosuch", default.options))
    with pytest.raises(SettingError, match="unknown option 'nosuch'; known: "):
        adapter.check_setting(default.replace(nosuch=1))


@pytest.mark.parametrize("engine", ENGINES)
def test_every_option_refuses_values_outside_its_range(engine: str) -> None:
    adapter = adapters.load(engine)
    default = adapter.default_setting(scenarios.build("slider_crank"))
    for option in adapter.options:
        bad: list[object] = ["no such choice"] if option.choices else [math.nan, math.inf, "word"]
        if not option.choices and math.isfinite(option.low):
            bad.append(option.low if option.low_open else option.low - 1)
        if not option.choices and math.isfinite(option.high):
            bad.append(2 * option.high + 1)
        for value in bad:
            with pytest.raises(SettingError, match=f"option {option.name} must be "):
                adapter.check_setting(default.replace(**{option.name: value}))  # type: ignore[arg-type]


def test_a_bad_setting_is_one_failed_run_not_an_exception() -> None:
    adapter = adapters.load("mujoco")
    scenario = scenarios.build("slider_crank")
    result = adapter.run(scenario, adapter.default_setting(scenario).replace(dt=0.0))
    assert result.status == "failed" and "option dt must be a float in (0, 1] s" in result.message


@pytest.mark.parametrize("engine", COMPARED)
def test_a_step_that_would_take_forever_is_refused_before_running(engine: str) -> None:
    """slider_crank's grid spans 2 pi / omega; a step of 1e-12 s would take ~1e11 steps."""
    from adapters.base import MAX_STEPS

    adapter = adapters.load(engine)
    scenario = scenarios.build("slider_crank")
    setting = adapter.default_setting(scenario).replace(dt=1e-12)
    result = adapter.run(scenario, setting)
    assert (
        result.status == "failed" and "would take" in result.message and f"{MAX_STEPS:.0e}" in result.message
    )
