"""What the harness and the report read of an engine without running it: the colour its rows are
drawn in and the distributions whose versions a run records. Each is declared on the engine's
adapter class (adapters.base.Adapter: `colour`, `packages`) and read here through the registry
(adapters.adapter_class), so no list of engines sits outside `adapters/<engine>/`. A run stores its
engines' declared colours with its results (`engine_colours` in the sidecar), and the report draws
them as stored (reports.render.plots gives any other name a colour of its palette).
"""

from __future__ import annotations

import functools
from collections.abc import Iterable

import adapters
from adapters.base import Adapter


@functools.cache
def declared(engine: str) -> type[Adapter] | None:
    """Engine `engine`'s adapter class, or None for a name the registry does not know or cannot
    load (cached: the registry's entry points are read once per name)."""
    try:
        return adapters.adapter_class(engine)
    except adapters.EngineUnavailable:
        return None


def colour(engine: str) -> str | None:
    """The colour `engine`'s adapter declares, or None (no colour declared, or no such engine)."""
    kind = declared(engine)
    return kind.colour if kind is not None and kind.colour else None


def colours(engines: Iterable[str]) -> dict[str, str]:
    """The declared colours of `engines`, as a run stores them beside its rows (an engine that
    declares none is left out: the report gives it one)."""
    found = {engine: colour(engine) for engine in engines}
    return {engine: c for engine, c in found.items() if c is not None}


def engine_packages() -> tuple[str, ...]:
    """The distributions every registered engine declares, in the registry's order, each once
    (an engine that cannot be loaded here declares none: its unavailability is recorded instead)."""
    found: dict[str, None] = {}
    for name in adapters.names():
        kind = declared(name)
        found.update(dict.fromkeys(kind.packages if kind is not None else ()))
    return tuple(found)
