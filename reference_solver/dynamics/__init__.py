"""Constrained dynamics in the textbook's augmented form, M q'' + C_q^T lambda = Q_e, C_q q'' = Q_d:
forward dynamics by coordinate partitioning, inverse dynamics of driven mechanisms, and the energy
accounting that checks both.

The names below are imported on first use: forward dynamics brings scipy.integrate, which a
kinematic solve never needs, and naming a method (dynamics.methods) should not load it."""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from reference_solver.dynamics.forward import DynamicAnalysis, simulate
    from reference_solver.dynamics.inverse import inverse_dynamics

__all__ = ["DynamicAnalysis", "inverse_dynamics", "simulate"]
_HOMES = {"DynamicAnalysis": "forward", "simulate": "forward", "inverse_dynamics": "inverse"}


def __getattr__(name: str) -> Any:
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(f"{__name__}.{home}"), name)
