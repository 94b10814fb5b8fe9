"""Constrained dynamics in the textbook's augmented form, M q'' + C_q^T lambda = Q_e, C_q q'' = Q_d:
forward dynamics by coordinate partitioning, inverse dynamics of driven mechanisms, and the energy
accounting that checks both."""

from reference_solver.dynamics.forward import DynamicAnalysis, simulate
from reference_solver.dynamics.inverse import inverse_dynamics

__all__ = ["DynamicAnalysis", "inverse_dynamics", "simulate"]
