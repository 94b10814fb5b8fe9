"""Errors of the reference solver. Each carries what a user needs to see where and why it failed."""

from __future__ import annotations

import numpy as np


class SolverError(Exception):
    """The kinematic analysis cannot go on.

    `time` is the time point, `q` the configuration reached (None before assembly), `rank_deficiency`
    how many independent rows C_q lost, `dependent_rows` the constraint rows involved.
    """

    def __init__(
        self,
        message: str,
        time: float | None = None,
        q: np.ndarray | None = None,
        rank_deficiency: int = 0,
        dependent_rows: tuple[str, ...] = (),
    ):
        super().__init__(message)
        self.time = time
        self.q = q
        self.rank_deficiency = rank_deficiency
        self.dependent_rows = dependent_rows


class MobilityError(SolverError):
    """The system is over-driven, under-driven or redundantly constrained."""


class AssemblyError(SolverError):
    """No configuration satisfies every constraint at the start time."""


class SingularConfigurationError(SolverError):
    """C_q became singular: a dead centre, a bifurcation or a jump to another assembly branch."""


class ConvergenceError(SolverError):
    """Newton-Raphson did not converge within the iteration limit at a regular configuration."""
