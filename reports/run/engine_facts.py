"""What the harness and the report read of an engine without running it: the colour its rows are
drawn in and the distributions whose versions a run records. Each is declared on the engine's
adapter class (adapters.base.Adapter: `colour`, `packages`) and read here through the registry
(adapters.adapter_class), so no list of engines sits outside `adapters/<engine>/`. A run stores its
engines' declared colours with its results (`engine_colours` in the sidecar), and the report draws
them as stored (reports.render.plots gives any other name a colour of its palette).

A plug-in's facts are its author's: a colour that is not a hex colour, or packages that are not a
tuple of names, is one warning line and treated as undeclared (a palette colour, no versions
recorded), so that a run never stores what its report cannot draw.
"""

from __future__ import annotations

import functools
import re
import sys
from collections.abc import Iterable

import adapters
from adapters.base import Adapter
from scenarios.shown import shown


@functools.cache
def declared(engine: str) -> type[Adapter] | None:
    """Engine `engine`'s adapter class, or None for a name the registry does not know or cannot
    load (cached: the registry's entry points are read once per name)."""
    try:
        return adapters.adapter_class(engine)
    except adapters.EngineUnavailable:
        return None


HEX_COLOUR = re.compile(r"#(?:[0-9a-fA-F]{3}){1,2}")
"""What an adapter's `colour` may be: `#rgb` or `#rrggbb`."""


def colour(engine: str) -> str | None:
    """The colour `engine`'s adapter declares, or None (no colour declared, or no such engine)."""
    kind = declared(engine)
    return _declared_colour(engine, kind.colour) if kind is not None and kind.colour else None


def _declared_colour(engine: str, value: object) -> str | None:
    """`value` if it is a colour, else None and one warning (said once per process)."""
    if isinstance(value, str) and HEX_COLOUR.fullmatch(value):
        return value
    warn_once(f"engine {engine}: colour {shown(value)} is not '#rrggbb' or '#rgb'; a palette colour is used")
    return None


def _packages(engine: str, kind: type[Adapter]) -> tuple[str, ...]:
    """The distributions `kind` declares, or none (and one warning) if they are not a tuple of names."""
    value = kind.packages
    if isinstance(value, tuple | list) and all(isinstance(p, str) and p for p in value):
        return tuple(value)
    warn_once(f"engine {engine}: packages {shown(value)} is not a tuple of names; no versions recorded")
    return ()


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
        found.update(dict.fromkeys(_packages(name, kind) if kind is not None else ()))
    return tuple(found)


@functools.cache
def warn_once(message: str) -> None:
    """One warning line on stderr, said once per process however often its fact is read."""
    print(f"mbxval: warning: {message}", file=sys.stderr)
