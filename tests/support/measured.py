"""Measured figures that several modules state: each engine's default and floor, the force errors
and A02 as specified. The tests of those engines hold them two-sided (tests.support.bounds), and
tests/test_docs_figures.py checks that the documentation states them, so that neither the code nor
the docs can drift from the other without a failure."""

from __future__ import annotations

KINEMATIC_DEFAULTS: dict[tuple[str, str], tuple[float, float, float]] = {
    # RK4 at 1/2000 of the turn, tc 128 steps, the regulariser scaled by 1e-8
    ("slider_crank", "mujoco"): (1.3e-11, 5.3e-11, 2.1e-10),
    ("four_bar", "mujoco"): (2.4e-11, 1.7e-10, 8.7e-10),
    ("cam_roller", "mujoco"): (2.5e-12, 8.5e-12, 3.0e-11),
    # GA3 at 1/2000 of the turn after its run-in: positions to Newton's tolerance
    ("slider_crank", "exudyn"): (1.1e-15, 1.6e-6, 4.8e-6),
    ("four_bar", "exudyn"): (1.3e-15, 8.7e-6, 7.3e-5),
    ("cam_roller", "exudyn"): (1.8e-15, 1.9e-7, 5.3e-7),
}
"""(scenario, engine): its errors per level at the engine's default setting, measured."""
DYNAMIC_DEFAULTS: dict[tuple[str, str], tuple[float, float, float]] = {
    # MuJoCo's time constant 1024 steps in free dynamics
    ("four_bar_gravity", "mujoco"): (6.1e-12, 3.2e-11, 4.3e-10),
    ("four_bar_gravity", "exudyn"): (1.6e-5, 8.2e-5, 9.2e-4),
    ("four_bar_gravity", "pinocchio"): (1.3e-9, 6.8e-9, 8.1e-8),
    ("andrews_squeezer", "mujoco"): (1.8e-10, 5.3e-10, 4.4e-9),
    ("andrews_squeezer", "exudyn"): (4.5e-5, 1.1e-4, 1.1e-3),
    ("andrews_squeezer", "pinocchio"): (1.5e-8, 3.8e-8, 3.5e-7),
    # the 9-link pendulum
    ("compound_pendulum", "mujoco"): (4.0e-12, 2.8e-11, 3.6e-10),
    ("compound_pendulum", "exudyn"): (2.7e-6, 1.8e-5, 1.9e-4),
    ("compound_pendulum", "pinocchio"): (6.3e-11, 4.4e-10, 5.8e-9),
}
"""(scenario, engine): its errors per level at the engine's default in free dynamics, measured
against the native forward dynamics (the compound pendulum with 9 links)."""
FLOORS: dict[tuple[str, str], tuple[float, float, float]] = {
    ("slider_crank", "mujoco"): (5.5e-12, 5.5e-12, 2.3e-11),
    ("four_bar_gravity", "mujoco"): (4.2e-12, 1.6e-11, 1.8e-10),
    ("andrews_squeezer", "pinocchio"): (1.3e-12, 2.3e-12, 2.0e-11),
    ("slider_crank", "exudyn"): (1.8e-15, 1.6e-8, 5.0e-6),
}
"""(scenario, engine): the errors at the floor of the engine's ladder
(tests/adapters/test_defaults_and_floors.py says which setting that is), measured."""
MUJOCO_FORCES: dict[str, tuple[float, float]] = {
    "slider_crank": (9.5e-11, 8.0e-5),
    "four_bar": (5.1e-10, 1.7e-4),
}
"""scenario: the force error over a whole turn at the default setting (the regulariser scaled by
1e-8, time constant 128 steps, the solver run to no improvement: adapters.mujoco.mjcf.Physics) and
with MuJoCo's own regulariser at 4 steps, measured, held two-sided (tests.support.bounds)."""
EXUDYN_FORCES: dict[tuple[str, str], float] = {
    ("slider_crank", "TR2"): 2.0e-6,
    ("slider_crank", "GA3"): 2.6e-6,  # after its run-in
    ("four_bar", "TR2"): 2.7e-5,
    ("four_bar", "GA3"): 3.5e-5,
}
"""(scenario, mode at the default step): the force error over a whole turn, measured
(GA3 after its run-in), held two-sided (tests.support.bounds)."""
A02_SPEC = (5.36e-09, 1.92e-11, 1.69e-07)
"""n_four_bar/spec (40 loops, 20 s, 20 singular passages) at h = 2e-5 on 400 output steps and the
passage times, on the compiled step: energy drift over the largest kinetic energy, the largest
rocker-to-crank angle (at a passage: 6.4e-12 to 1.9e-11 over the 20; 2.5e-13 at every other output),
the crank's distance to the reduced equation. Measured with the steps near each passage careful
and the step across it placed (dynamics.passage)."""
