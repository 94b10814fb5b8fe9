"""Scoring a trajectory: the truths it is measured against, its per-level errors, the engines'
agreement, energy drift, forces, and the checks a run makes of itself with no truth."""
