"""An engine's settings: its typed, ranged options and one setting (a mode with option values), the
point of its accuracy-for-time trade-off that a run is made at."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from adapters.failures import SettingError
from scenarios.family import declared_value, range_text

OptionValue = float | int | str | bool


@dataclass(frozen=True)
class Option:
    """One engine option: its type (`kind`), range (`low`..`high`, `low_open` excluding `low`) or
    `choices`, and unit. Its default is the engine's `default_setting` (it may depend on the scenario's
    grid, such as a step size)."""

    name: str
    kind: type = float
    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    choices: tuple[str, ...] = ()
    unit: str = ""
    help: str = ""

    def describe(self) -> str:
        if self.choices:
            return "one of " + ", ".join(self.choices)
        article = "an" if self.kind is int else "a"
        return (
            f"{article} {self.kind.__name__} in {range_text(self.low, self.high, self.low_open, self.unit)}"
        )

    def check(self, engine: str, value: OptionValue) -> OptionValue:
        """`value` as the option's type; SettingError with the range otherwise."""
        typed = declared_value(
            value,
            text=self.kind is str,
            integer=self.kind is int,
            low=self.low,
            high=self.high,
            low_open=self.low_open,
            choices=self.choices,
        )
        if typed is None:
            raise SettingError(f"{engine}: option {self.name} must be {self.describe()}, got {value!r}")
        return typed


@dataclass(frozen=True)
class Setting:
    """One point of an engine's accuracy-for-time trade-off. Settings with the same `mode` form one
    work-precision curve (say MuJoCo RK4 across step sizes)."""

    mode: str
    options: tuple[tuple[str, OptionValue], ...] = ()

    @classmethod
    def of(cls, mode: str, **options: OptionValue) -> Setting:
        return cls(mode, tuple(sorted(options.items())))

    def get(self, key: str, default: OptionValue | None = None) -> Any:
        return dict(self.options).get(key, default)

    def __getitem__(self, key: str) -> Any:
        return dict(self.options)[key]

    def replace(self, **options: OptionValue) -> Setting:
        return Setting.of(self.mode, **{**dict(self.options), **options})

    @property
    def label(self) -> str:
        """Short, stable text such as `RK4 dt=0.0001 solref=0.0002`."""
        parts = [self.mode] + [f"{k}={_fmt(v)}" for k, v in self.options]
        return " ".join(parts)


def _fmt(value: OptionValue) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)
