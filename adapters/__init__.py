"""Engine adapters, one subpackage per engine, each imported only when that engine is asked for;
engines from other packages arrive through the `mbxval.engines` entry-point group.

`ENGINES` is the registry: one line per built-in engine. Everything else about an engine (its modes,
settings, colour, packages, stress settings) is declared on its adapter class, read through
`adapter_class(name)`, so adding an engine touches its subpackage, one line here and its tests.
`load(name)` returns an adapter instance, or raises EngineUnavailable with the reason (the engine is
not installed, or its module failed to import), so a missing engine costs only its own rows.

A plug-in is another package's code, run here: whatever its import raises (any exception, a syntax
error) or declares wrongly makes it one warning line, `mbxval: warning: engine plug-in NAME could
not be loaded: ...`, said once per process, and leaves that engine out of `names()`; it never takes a
command down.
"""

from __future__ import annotations

import functools
import importlib
import sys
from importlib.metadata import entry_points

from adapters.base import Adapter
from scenarios.shown import one_line, shown

NATIVE = "reference"
"""The engine name of the native textbook solver (adapters.reference)."""

ENGINES: dict[str, tuple[str, str]] = {
    NATIVE: ("adapters.reference", "ReferenceAdapter"),
    "mujoco": ("adapters.mujoco", "MujocoAdapter"),
    "exudyn": ("adapters.exudyn", "ExudynAdapter"),
    "pinocchio": ("adapters.pinocchio", "PinocchioAdapter"),
    "drake": ("adapters.drake", "DrakeAdapter"),
}


GROUP = "mbxval.engines"
"""The entry-point group an installed package adds its engine to: `name = "module:AdapterClass"`."""


class EngineUnavailable(RuntimeError):
    """The engine cannot be used here; the message says why."""


def _plugins() -> dict[str, tuple[str, str]]:
    """Every engine the entry-point group adds, loadable or not, by name (a built-in name wins)."""
    found = {}
    for point in entry_points(group=GROUP):
        if point.name not in ENGINES:
            module_name, _, class_name = point.value.partition(":")
            found[point.name] = (module_name.strip(), class_name.strip())
    return dict(sorted(found.items()))


def installed() -> dict[str, tuple[str, str]]:
    """The plug-in engines that load here, by name; a broken one is warned about and left out."""
    return {name: where for name, where in _plugins().items() if plugin_problem(name, *where) is None}


def names() -> list[str]:
    """The built-in engines, then the installed ones."""
    return [*ENGINES, *installed()]


@functools.cache
def plugin_problem(name: str, module_name: str, class_name: str) -> str | None:
    """Why plug-in `name` cannot be loaded, or None; the first time, said on stderr as one warning
    (cached: a broken module is imported once per process, its warning given once)."""
    try:
        _load_class(name, module_name, class_name, f"engine plug-in {name} could not be loaded")
    except EngineUnavailable as error:
        print(f"mbxval: warning: {error}", file=sys.stderr)
        return str(error)
    return None


def adapter_class(name: str) -> type[Adapter]:
    """Engine `name`'s adapter class, whose class attributes declare its facts (Adapter)."""
    if name in ENGINES:
        return _load_class(name, *ENGINES[name], f"engine '{name}' is not available")
    plugins = _plugins()
    if name not in plugins:
        raise EngineUnavailable(f"unknown engine '{name}'; known: {', '.join(names())}")
    problem = plugin_problem(name, *plugins[name])
    if problem is not None:
        raise EngineUnavailable(problem)
    return _load_class(name, *plugins[name], f"engine plug-in {name} could not be loaded")


def _load_class(name: str, module_name: str, class_name: str, unavailable: str) -> type[Adapter]:
    """The class `module_name:class_name`, checked to be engine `name`'s adapter; EngineUnavailable
    starting with `unavailable` otherwise."""
    if not module_name or not class_name:
        raise EngineUnavailable(f"{unavailable}: its entry point must read 'module:AdapterClass'")
    try:
        module = importlib.import_module(module_name)
        kind = getattr(module, class_name)
    except (Exception, SystemExit) as error:  # an import runs the engine's code: it may raise anything
        raise EngineUnavailable(f"{unavailable}: {_described(error)}") from error
    if not (isinstance(kind, type) and issubclass(kind, Adapter)):
        raise EngineUnavailable(f"{unavailable}: {module_name}:{class_name} is not an Adapter subclass")
    if kind.name != name:
        raise EngineUnavailable(f"{unavailable}: its adapter calls itself {shown(kind.name)}")
    return kind


def _described(error: BaseException) -> str:
    """An import's error on one line: a missing module as Python says it, anything else with its type."""
    text = str(error) if isinstance(error, ImportError) else f"{type(error).__name__}: {error}"
    return one_line(text)


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
    kind = adapter_class(name)
    try:
        return kind()
    except Exception as error:  # a plug-in's constructor is its own code
        raise EngineUnavailable(f"engine '{name}' is not available: {_described(error)}") from error
