"""The native forward-dynamics methods by name, apart from their integrators, so that naming them
(the native adapter's modes) imports no integrator."""

METHODS = ("DOP853", "Radau")
"""The partitioned method's integrators (scipy.integrate's, dynamics.forward)."""
ALI3P = "ali3p"
"""The second native method: index-3 augmented Lagrangian with projections (ali3p.py), at a fixed
step; it passes singular configurations, where the partitioned method cannot."""
ALI3P_STEP = 1e-4
"""ALI3-P's default largest step (s)."""
