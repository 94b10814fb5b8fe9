"""Engine modes and options as the user gives them (`--mode`, `--setting KEY=VALUE`), checked
against one declared range per option before anything is built: an unknown key or mode is an error
listing the known ones, a value outside its range an error naming the range.

An adapter that declares its options itself (an `OPTIONS` mapping of OptionRange) is checked
against that; for the others the ranges are declared here, by engine.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from dataclasses import dataclass

from adapters.base import Adapter, OptionValue, Setting
from reports.cli.usage import UsageError
from scenarios import Scenario


@dataclass(frozen=True)
class OptionRange:
    """A numeric option: low < value <= high (or low <= value with `closed`), in `unit`."""

    low: float
    high: float
    unit: str = ""
    closed: bool = False
    integer: bool = False

    def check(self, key: str, value: OptionValue) -> None:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise UsageError(f"--setting {key} must be a number, got '{value}'")
        inside = (self.low <= value if self.closed else self.low < value) and value <= self.high
        if not (math.isfinite(value) and inside) or (self.integer and value != int(value)):
            left = "[" if self.closed else "("
            unit = f" {self.unit}" if self.unit else ""
            kind = "an integer" if self.integer else "a number"
            raise UsageError(
                f"--setting {key} must be {kind} in {left}{self.low:g}, {self.high:g}]{unit}, got {value}"
            )


STEP = OptionRange(0.0, 1.0, "s")
TOLERANCE = OptionRange(0.0, 1.0)
OPTIONS: dict[str, dict[str, OptionRange | tuple[str, ...]]] = {
    "reference": {"tolerance": TOLERANCE},
    "mujoco": {
        "dt": STEP,
        "tc_steps": OptionRange(1.0, 1e6, "time steps", closed=True),
        "impedance": OptionRange(0.0, 1.0, closed=False),
        "contact_impedance": OptionRange(0.0, 1.0),
        "preload": OptionRange(0.0, 1e6),
        "mass_scale": OptionRange(0.0, 1e12),
    },
    "exudyn": {
        "dt": STEP,
        "rho": OptionRange(0.0, 1.0, closed=True),
        "tol": TOLERANCE,
        "mass_scale": OptionRange(0.0, 1e12),
        "cams": ("native", "user"),
    },
    "pinocchio": {
        "dt": STEP,
        "tol": TOLERANCE,
        "kp": OptionRange(0.0, 1e12, closed=True),
        "kd": OptionRange(0.0, 1e12, closed=True),
        "gears": ("mimic", "row"),
    },
}


def declared(adapter: Adapter) -> Mapping[str, OptionRange | tuple[str, ...]]:
    own = getattr(adapter, "OPTIONS", None)
    return own if isinstance(own, Mapping) else OPTIONS.get(adapter.name, {})


def known_modes(adapter: Adapter, scenario: Scenario, default: Setting) -> list[str]:
    own = getattr(adapter, "MODES", None) or getattr(sys.modules.get(type(adapter).__module__), "MODES", None)
    modes = [default.mode, *(s.mode for s in adapter.sweep(scenario))]
    if own is not None:
        modes += list(own)
    return list(dict.fromkeys(modes))


def with_mode(adapter: Adapter, scenario: Scenario, setting: Setting, mode: str) -> Setting:
    """The setting in another mode; UsageError listing the known modes for an unknown one."""
    known = known_modes(adapter, scenario, setting)
    if mode not in known:
        raise UsageError(f"unknown {adapter.name} mode '{mode}'; known: {', '.join(known)}")
    return Setting(mode, setting.options)


def with_options(adapter: Adapter, setting: Setting, overrides: Mapping[str, OptionValue]) -> Setting:
    """The setting with the options overridden, each checked against its declared range."""
    ranges = declared(adapter)
    known = list(dict.fromkeys([*dict(setting.options), *ranges]))
    for key, value in overrides.items():
        if key not in known:
            raise UsageError(f"unknown {adapter.name} setting '{key}'; known: {', '.join(known) or 'none'}")
        limit = ranges.get(key)
        if isinstance(limit, OptionRange):
            limit.check(key, value)
        elif limit is not None and value not in limit:
            raise UsageError(f"--setting {key} must be one of {', '.join(limit)}, got '{value}'")
        elif limit is None and isinstance(value, float) and not math.isfinite(value):
            raise UsageError(f"--setting {key} must be a finite number, got {value}")
    return setting.replace(**overrides) if overrides else setting
