"""Engine adapters, one subpackage per engine, each imported only when that engine is asked for;
engines from other packages arrive through the `mbxval.engines` entry-point group.

`ENGINES` is the registry: one line per built-in engine. Everything else about an engine (its modes,
settings, colour, packages, stress settings) is declared on its adapter class, read through
`adapter_class(name)`, so adding an engine touches its subpackage, one line here and its tests.
`load(name)` returns an adapter instance, or raises EngineUnavailable with the reason (the engine is
not installed, or its module failed to import), so a missing engine costs only its own rows.
"""

from __future__ import annotations

import importlib
from importlib.metadata import entry_points

from adapters.base import Adapter

NATIVE = "reference"
"""The engine name of the native textbook solver (adapters.reference)."""

ENGINES: dict[str, tuple[str, str]] = {
    NATIVE: ("adapters.reference", "ReferenceAdapter"),
    "mujoco": ("adapters.mujoco", "MujocoAdapter"),
    "exudyn": ("adapters.exudyn", "ExudynAdapter"),
    "pinocchio": ("adapters.pinocchio", "PinocchioAdapter"),
}


GROUP = "mbxval.engines"
"""The entry-point group an installed package adds its engine to: `name = "module:AdapterClass"`."""


class EngineUnavailable(RuntimeError):
    """The engine cannot be used here; the message says why."""


def installed() -> dict[str, tuple[str, str]]:
    """Engines other packages add through the entry-point group, by name (a built-in name wins)."""
    found = {}
    for point in entry_points(group=GROUP):
        module_name, _, class_name = point.value.partition(":")
        if point.name not in ENGINES and class_name:
            found[point.name] = (module_name.strip(), class_name.strip())
    return dict(sorted(found.items()))


def names() -> list[str]:
    """The built-in engines, then the installed ones."""
    return [*ENGINES, *installed()]


def adapter_class(name: str) -> type[Adapter]:
    """Engine `name`'s adapter class, whose class attributes declare its facts (Adapter)."""
    known = {**ENGINES, **installed()}
    if name not in known:
        raise EngineUnavailable(f"unknown engine '{name}'; known: {', '.join(known)}")
    module_name, class_name = known[name]
    try:
        module = importlib.import_module(module_name)
        kind = getattr(module, class_name)
    except (ImportError, AttributeError) as error:
        raise EngineUnavailable(f"engine '{name}' is not available: {error}") from error
    if not (isinstance(kind, type) and issubclass(kind, Adapter)):
        raise EngineUnavailable(f"engine {name!r}: {module_name}:{class_name} is not an Adapter subclass")
    if kind.name != name:
        raise EngineUnavailable(f"engine '{name}': its adapter calls itself '{kind.name}'")
    return kind


def exporters() -> list[str]:
    """The engines that write a model file of their own (their adapter overrides `export`), in the
    registry's order; an engine that cannot be loaded here is left out."""
    found = []
    for name in names():
        try:
            if adapter_class(name).export is not Adapter.export:
                found.append(name)
        except EngineUnavailable:
            continue
    return found


def load(name: str) -> Adapter:
    """An instance of engine `name`'s adapter."""
    return adapter_class(name)()
