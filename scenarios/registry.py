"""The catalogue of mechanism families, their parameters and named variants."""

from __future__ import annotations

import difflib
from collections.abc import Mapping

from scenarios.families import (
    andrews_squeezer,
    cam_flat_face,
    cam_knife_edge,
    cam_roller,
    compound_pendulum,
    four_bar,
    four_bar_chain,
    four_bar_gravity,
    n_four_bar,
    planetary_gears,
    rack_pinion,
    slider_crank,
    slider_crank_spring,
    spur_gears,
    stiff_spring,
)
from scenarios.family import Family
from scenarios.limits import check_grid, check_t_end, dense
from scenarios.scenario import ParameterValue, Scenario, ScenarioError

FAMILIES: tuple[Family, ...] = tuple(
    module.FAMILY
    for module in (
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
)


def all_families() -> dict[str, Family]:
    """Every family by name, in catalogue order."""
    return {f.name: f for f in FAMILIES}


def _suggest(word: str, choices: list[str]) -> str:
    close = difflib.get_close_matches(word, choices, n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


def family(name: str) -> Family:
    """The family called `name`; ScenarioError naming the known ones otherwise."""
    known = all_families()
    if name not in known:
        raise ScenarioError(
            f"unknown scenario '{name}'{_suggest(name, list(known))}; known: {', '.join(known)}"
        )
    return known[name]


def singular_passages(scenario: Scenario) -> str:
    """Why `scenario`'s motion passes singular configurations, as its family declares
    (Family.singular_passages); '' where it does not or its family is not built in."""
    found = all_families().get(scenario.family)
    return found.singular_passages if found is not None else ""


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
    values: dict[str, ParameterValue] = fam.defaults
    values.update(fam.variants.get(variant, {}))
    for key, value in (overrides or {}).items():
        if key not in fam.parameters:
            raise ScenarioError(
                f"{name}: unknown parameter '{key}'{_suggest(key, list(fam.parameters))}; "
                f"known: {', '.join(fam.parameters)}"
            )
        values[key] = value
    params = {key: fam.parameters[key].check(name, key, value) for key, value in values.items()}
    try:
        scenario = fam.build(params, variant)
    except ScenarioError:
        raise
    except (ArithmeticError, ValueError) as error:  # a combination no single range excludes
        raise ScenarioError(f"{name}: cannot be built with these parameters: {error}") from error
    check_t_end(scenario.name, scenario.t_end)
    check_grid(scenario.name, scenario.steps + 1, len(scenario.bodies), dense(scenario))
    return scenario


def is_stress_variant(variant: str) -> bool:
    """Stress variants (named `stress...`) are made to break solvers: singular, extreme, long."""
    return variant.startswith("stress")


def catalogue(include_stress: bool = False, include_dynamic: bool = False) -> list[str]:
    """Every scenario name: each family's default and its named variants as `family/variant`.

    Stress variants are left out unless `include_stress`: they belong to the stress suite, not to
    what runs or is checked for every scenario. Dynamic families are left out unless `include_dynamic`:
    the kinematic suites and checks do not apply to them.
    """
    names = []
    for fam in all_families().values():
        if fam.dynamic and not include_dynamic:
            continue
        names.append(fam.name)
        names.extend(f"{fam.name}/{v}" for v in fam.variants if include_stress or not is_stress_variant(v))
    return names
