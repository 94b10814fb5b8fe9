"""The catalogue of mechanism families, their parameters and named variants."""

from __future__ import annotations

import difflib
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from scenarios.scenario import ParameterValue, Scenario, ScenarioError


@dataclass(frozen=True)
class Family:
    """A mechanism family: defaults for every parameter, named variants, and a builder.

    `build(params, variant)` receives every parameter, already typed, and returns the scenario.
    """

    name: str
    summary: str
    defaults: Mapping[str, ParameterValue]
    build: Callable[[dict[str, ParameterValue], str], Scenario]
    variants: Mapping[str, Mapping[str, ParameterValue]]
    dynamic: bool = False
    """Forward dynamics (gravity, forces) rather than a driven kinematic analysis: left out of the
    kinematic catalogue until the engines compare dynamics."""


def _families() -> dict[str, Family]:
    from scenarios import (
        cam_flat_face,
        cam_knife_edge,
        cam_roller,
        four_bar,
        four_bar_chain,
        planetary_gears,
        rack_pinion,
        slider_crank,
        spur_gears,
    )

    from scenarios.families import (
        andrews_squeezer,
        compound_pendulum,
        four_bar_gravity,
        n_four_bar,
        slider_crank_spring,
        stiff_spring,
    )

    modules = (
        slider_crank,
        four_bar,
        spur_gears,
        planetary_gears,
        rack_pinion,
        cam_knife_edge,
        cam_roller,
        cam_flat_face,
        four_bar_chain,
        compound_pendulum,
        four_bar_gravity,
        slider_crank_spring,
        andrews_squeezer,
        n_four_bar,
        stiff_spring,
    )
    return {m.FAMILY.name: m.FAMILY for m in modules}


def families() -> dict[str, Family]:
    """Every family by name, in catalogue order."""
    return _families()


def _suggest(word: str, choices: list[str]) -> str:
    close = difflib.get_close_matches(word, choices, n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


def family(name: str) -> Family:
    """The family called `name`; ScenarioError naming the known ones otherwise."""
    known = families()
    if name not in known:
        raise ScenarioError(
            f"unknown scenario '{name}'{_suggest(name, list(known))}; known: {', '.join(known)}"
        )
    return known[name]


def _typed(family_name: str, key: str, default: ParameterValue, value: ParameterValue) -> ParameterValue:
    if isinstance(default, str):
        return str(value)
    try:
        if isinstance(default, int) and not isinstance(default, bool):
            number = float(value)
            if number != int(number):
                raise ValueError
            return int(number)
        return float(value)
    except (TypeError, ValueError):
        kind = "an integer" if isinstance(default, int) else "a number"
        raise ScenarioError(f"{family_name}: parameter {key} must be {kind}, got {value!r}") from None


def build(
    name: str, variant: str = "default", overrides: Mapping[str, ParameterValue] | None = None
) -> Scenario:
    """Build scenario `name` (or `family/variant`) with parameter overrides given as values or strings."""
    if "/" in name:
        name, variant = name.split("/", 1)
    fam = family(name)
    if variant != "default" and variant not in fam.variants:
        raise ScenarioError(
            f"{name}: unknown variant '{variant}'{_suggest(variant, list(fam.variants))}; "
            f"known: {', '.join(['default', *fam.variants])}"
        )
    params: dict[str, ParameterValue] = dict(fam.defaults)
    params.update(fam.variants.get(variant, {}))
    for key, value in (overrides or {}).items():
        if key not in fam.defaults:
            raise ScenarioError(
                f"{name}: unknown parameter '{key}'{_suggest(key, list(fam.defaults))}; "
                f"known: {', '.join(fam.defaults)}"
            )
        params[key] = _typed(name, key, fam.defaults[key], value)
    return fam.build(params, variant)


def is_stress_variant(variant: str) -> bool:
    """Stress variants (named `stress...`) are made to break solvers: singular, extreme, long."""
    return variant.startswith("stress")


def catalogue(include_stress: bool = False, include_dynamic: bool = False) -> list[str]:
    """Every scenario name: each family's default and its named variants as `family/variant`.

    Stress variants are left out unless `include_stress`: they belong to the stress suite, not to
    what runs or is checked for every scenario.
    """
    names = []
    for fam in families().values():
        if fam.dynamic and not include_dynamic:
            continue
        names.append(fam.name)
        names.extend(f"{fam.name}/{v}" for v in fam.variants if include_stress or not is_stress_variant(v))
    return names
