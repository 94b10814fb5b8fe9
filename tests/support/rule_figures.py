"""The measured figures of docs/settings-rule.md's sweeps and docs/a02.md's table: each engine's test
recomputes them with the real engine and holds them within TOLERANCE (tests/adapters/mujoco/
test_rule_figures.py, tests/adapters/exudyn/test_rule_figures.py, tests/adapters/
test_a02_figures.py), and tests/test_docs_rule_figures.py checks that the pages state them as
given here, so neither the pages nor the engines can drift from these tables without a failure.
Errors are relative per level (P, V, A), as scoring.level_error measures them against the harness
truth; a time constant is in steps of the setting's dt."""

from __future__ import annotations

from tests.support.measured import measured_table

TOLERANCE = 1.3
"""A recomputed figure stays within this factor of the one stated, either way: the pages give two
digits, and an engine release may move its round-off."""

# MuJoCo, driven scenes at the rule's step
MUJOCO_OWN_TC: dict[float, tuple[float, float, float]] = {
    2.0: (6.9e-8, 1.7e-5, 4.0e-3),
    4.0: (7.3e-8, 1.9e-6, 2.2e-4),
    8.0: (2.7e-7, 7.0e-7, 1.4e-5),
    16.0: (1.1e-6, 2.8e-6, 1.9e-5),
}
"""slider_crank with MuJoCo's own regulariser at each time constant."""
MUJOCO_SCALED_TC: dict[tuple[str, float], tuple[float, float, float]] = {
    ("slider_crank", 64.0): (4.4e-11, 4.0e-10, 3.0e-9),
    ("slider_crank", 128.0): (1.3e-11, 5.3e-11, 2.1e-10),
    ("slider_crank", 256.0): (5.5e-12, 5.5e-12, 2.3e-11),
    ("four_bar", 64.0): (9.6e-11, 8.9e-10, 7.0e-9),
    ("four_bar", 128.0): (2.4e-11, 1.7e-10, 8.7e-10),
    ("four_bar", 256.0): (1.0e-11, 5.5e-11, 1.7e-10),
}
"""(scenario, time constant) with the regulariser scaled by 1e-8 (the rule's)."""

# MuJoCo, free dynamics at the rule's step, the regulariser scaled by 1e-8
MUJOCO_FREE_TC: dict[tuple[str, float], tuple[float, ...]] = {
    (scenario, float(tc)): figures for (scenario, tc), figures in measured_table("mujoco_free_tc").items()
}
"""(scenario, time constant), the time-constant form; at 128 and 1024 steps the direct form
(solref=direct) gives the same figures (tests/adapters/mujoco/test_rule_figures.py)."""
MUJOCO_SINGULAR_TC: dict[float, tuple[float, float, float]] = {
    1024.0: (1.5e-8, 4.3e-8, 1.3e-6),
    128.0: (3.3e-9, 1.7e-8, 6.0e-7),
    64.0: (8.4e-10, 4.1e-9, 1.9e-7),
    32.0: (6.0e-10, 7.0e-10, 3.9e-8),
}
"""n_four_bar over its first second (40 outputs), the regulariser scaled by 1e-8, per time constant."""
MUJOCO_SINGULAR_WEIGHTS: dict[float, tuple[float, float, float]] = {
    1e-10: (5.9e-10, 1.4e-9, 4.2e-8),
    1e-12: (1.4e-10, 7.1e-10, 9.1e-9),
}
"""n_four_bar over its first second at 1024 steps, per regulariser scale."""
MUJOCO_OFF_BRANCH = 0.57
"""four_bar_gravity's positions at its default with the regulariser scaled by 1e-10 (it leaves its
branch; at 1e-12 the run diverges)."""
MUJOCO_SINGULAR_SAG = 3.0e-5
"""n_four_bar's positions over its first second (links of 1 m) on the ladder's rung with the
regulariser scaled by 1e-6 at 128 steps."""
MUJOCO_SPLINE_CAM: dict[tuple[int, float], tuple[float, float, float]] = {
    (512, 4.0): (7.9e-5, 4.8e-3, 3.0),
    (512, 16.0): (3.4e-4, 2.6e-3, 0.79),
    (1024, 8.0): (8.6e-5, 2.0e-3, 0.70),
    (1024, 16.0): (2.8e-4, 1.6e-3, 0.41),
    (2048, 8.0): (6.8e-5, 1.7e-3, 0.43),
    (2048, 16.0): (2.8e-4, 1.6e-3, 0.25),
}
"""cam_roller/spline by contact, MuJoCo's own regulariser: (facets, contact time constant)."""
MUJOCO_SPLINE_CAM_RINGING = ((1024, 32.0), (2048, 32.0), (4096, 16.0))
"""(facets, time constant) at which the follower rings on the vertices: accelerations above
RINGING."""
RINGING = 10.0

# Exudyn: four_bar at 2000 outputs over its turn, GA3 at the default step
EXUDYN_REMEDIES: dict[str, tuple[dict[str, float], float, float]] = {
    "none": ({"run_in": 0}, 6.1e-2, 106),
    "rho 0.5": ({"run_in": 0, "rho": 0.5}, 1.2e-2, 12),
    "rho 0.6": ({"run_in": 0, "rho": 0.6}, 1.4e-2, 18),
    "rho 0.99": ({"run_in": 0, "rho": 0.99}, 6.3e-1, 913),
    "run-in 50": ({"run_in": 50}, 1.7e-2, 62),
    "run-in 200": ({"run_in": 200}, 7.3e-5, 0),
    "run-in 50 rho 0.5": ({"run_in": 50, "rho": 0.5}, 1.1e-4, 0),
    "run-in 50 rho 0.6": ({"run_in": 50, "rho": 0.6}, 9.3e-5, 0),
    "run-in 50 rho 0": ({"run_in": 50, "rho": 0.0}, 4.0e-4, 0),
}
"""remedy: (the default's options changed, acceleration error, steps the start-up lasts by
scoring.startup: 0 where no transient shows)."""
EXUDYN_RHO_ZERO = (1.5e-2, 2)
"""rho 0 from the exact start: (acceleration error, start-up steps)."""
EXUDYN_INDEX_2 = (2.8e-6, 5.5e-5)
"""TR2 (index 2) at the default step: (positions, accelerations); no transient."""
EXUDYN_RUN_IN_STEPS = 250
"""The default's run-in at rho 0.9: the least n with n 0.9^n <= 1e-9."""
EXUDYN_EXACT_START: dict[str, tuple[float, float]] = {
    "four_bar": (7.8e2, 6.3e-3),
    "slider_crank": (1.3e3, 6.3e-3),
    "cam_roller": (5.8e3, 3.8e-2),
}
"""scenario on its own grid, GA3 with run_in=0: (startup_excess, startup_time in s)."""
EXUDYN_FREE_EXCESS = {"four_bar_gravity": 0.89, "andrews_squeezer": 0.27}
"""startup_excess at the default in free dynamics (no run-in, Exudyn's own start)."""
EXUDYN_SPLINE_KNOTS = 1.7e-4
"""cam_roller/spline's accelerations at the default: the transient restarted at each knot."""

# the native engine on IFToMM A02 (n_four_bar), ALI3-P, 400 outputs
A02_TABLE: dict[tuple[str, float | None], tuple[float, float]] = {
    ("n_four_bar", None): (2.2e-4, 5.6e-6),
    ("n_four_bar", 1e-4): (1.0e-5, 1.1e-7),
    ("n_four_bar", 1e-3): (1.2e-3, 1.1e-5),
    ("n_four_bar/spec", None): (2.5e-5, 3.1e-7),
}
"""(scenario, dt or None for the default): (B0's error, energy drift over the largest kinetic
energy); N = 2 over 10 s, the spec variant N = 40 over 20 s. The rockers' angle to the crank is
at round-off in every case (below ROCKERS)."""
A02_ROCKERS = 1e-11
"""rad: the bound the rockers' largest angle to the crank stays under on every case of A02_TABLE."""
