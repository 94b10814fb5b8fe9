"""Engine adapters, one module per engine, each imported only when that engine is asked for.

`load(name)` returns an adapter instance, or raises EngineUnavailable with the reason (the engine is
not installed, or its module failed to import), so a missing engine costs only its own rows.
"""

from __future__ import annotations

import importlib

from adapters.base import Adapter

ENGINES: dict[str, tuple[str, str]] = {
    "reference": ("adapters.reference", "ReferenceAdapter"),
    "mujoco": ("adapters.mujoco", "MujocoAdapter"),
    "exudyn": ("adapters.exudyn", "ExudynAdapter"),
    "pinocchio": ("adapters.pinocchio", "PinocchioAdapter"),
}


class EngineUnavailable(RuntimeError):
    """The engine cannot be used here; the message says why."""


def names() -> list[str]:
    return list(ENGINES)


def load(name: str) -> Adapter:
    """An instance of engine `name`'s adapter."""
    if name not in ENGINES:
        raise EngineUnavailable(f"unknown engine '{name}'; known: {', '.join(ENGINES)}")
    module_name, class_name = ENGINES[name]
    try:
        module = importlib.import_module(module_name)
    except ImportError as error:
        raise EngineUnavailable(f"engine '{name}' is not available: {error}") from error
    adapter: Adapter = getattr(module, class_name)()
    return adapter
