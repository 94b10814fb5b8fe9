"""The textbook formulation of planar kinematics: absolute coordinates, constraints, Newton-Raphson,
velocity and acceleration solves, and the diagnostics of singular configurations."""

from reference_solver.analysis import analyse, solve
from reference_solver.errors import (
    AssemblyError,
    ConvergenceError,
    MobilityError,
    SingularConfigurationError,
    SolverError,
)
from reference_solver.residual import constraint_residual
from reference_solver.solution import Analysis
from reference_solver.system import ConstraintSystem

__all__ = [
    "Analysis",
    "AssemblyError",
    "ConstraintSystem",
    "ConvergenceError",
    "MobilityError",
    "SingularConfigurationError",
    "SolverError",
    "analyse",
    "constraint_residual",
    "solve",
]
