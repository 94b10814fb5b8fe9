"""What the harness and the report read of an engine without running it: the colour its rows are
drawn in and the distributions whose versions a run records. Each is declared on the engine's
adapter class (adapters.base.Adapter: `colour`, `packages`) and read here through the registry
(adapters.adapter_class), so no list of engines sits outside `adapters/<engine>/`. A run stores its
engines' colours with its results (`engine_colours` in the sidecar), so a stored report keeps them.
"""

from __future__ import annotations

import functools
from collections.abc import Iterable

import adapters
from adapters.base import Adapter

PALETTE = ("#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf", "#ff7f0e")
"""The colours of an engine that declares none and of a label that is no engine (an imported
trajectory's), chosen by its name so that it keeps its colour from one report to the next."""


@functools.cache
def declared(engine: str) -> type[Adapter] | None:
    """Engine `engine`'s adapter class, or None for a name the registry does not know or cannot
    load (cached: the registry's entry points are read once per name)."""
    try:
        return adapters.adapter_class(engine)
    except adapters.EngineUnavailable:
        return None


def colour(engine: str) -> str:
    """The colour `engine`'s rows are drawn in: its adapter's declaration, else one of PALETTE."""
    kind = declared(engine)
    if kind is not None and kind.colour:
        return kind.colour
    return PALETTE[sum(map(ord, engine)) % len(PALETTE)]


def colours(engines: Iterable[str]) -> dict[str, str]:
    """Each engine's colour, as a run stores them beside its rows."""
    return {engine: colour(engine) for engine in engines}


def engine_packages() -> tuple[str, ...]:
    """The distributions every registered engine declares, in the registry's order, each once
    (an engine that cannot be loaded here declares none: its unavailability is recorded instead)."""
    found: dict[str, None] = {}
    for name in adapters.names():
        kind = declared(name)
        found.update(dict.fromkeys(kind.packages if kind is not None else ()))
    return tuple(found)
