"""Measured figures that several modules state (their tables in measured.toml, read by `measured_table`,
with the tables of single test modules): each engine's default and floor, the force errors and A02
as specified. The tests of those engines hold them two-sided (tests.support.bounds), and
tests/test_docs_figures.py checks that the documentation states them, so that neither the code nor
the docs can drift from the other without a failure."""

from __future__ import annotations

import functools
import tomllib
from pathlib import Path
from typing import Any

MEASURED = Path(__file__).with_name("measured.toml")


@functools.cache
def _tables() -> dict[str, Any]:
    with MEASURED.open("rb") as file:
        return tomllib.load(file)


def measured_table(table: str) -> dict[Any, tuple[float, ...]]:
    """Table `table` of measured.toml, in its order: each row's leading strings are its key (one
    string, or a tuple of them) and the numbers after them its figures."""
    found: dict[Any, tuple[float, ...]] = {}
    for row in _tables()[table]:
        k = next(i for i, item in enumerate(row) if not isinstance(item, str))
        found[row[0] if k == 1 else tuple(row[:k])] = tuple(float(v) for v in row[k:])
    return found


KINEMATIC_DEFAULTS: dict[tuple[str, str], tuple[float, ...]] = measured_table("kinematic_defaults")
"""(scenario, engine): its errors per level at the engine's default setting, measured."""
DYNAMIC_DEFAULTS: dict[tuple[str, str], tuple[float, ...]] = measured_table("dynamic_defaults")
"""(scenario, engine): its errors per level at the engine's default in free dynamics, measured
against the native forward dynamics (the compound pendulum with 9 links)."""
FLOORS: dict[tuple[str, str], tuple[float, ...]] = measured_table("floors")
"""(scenario, engine): the errors at the floor of the engine's ladder
(tests/adapters/test_defaults_and_floors.py says which setting that is), measured."""
MUJOCO_FORCES: dict[str, tuple[float, ...]] = measured_table("mujoco_forces")
"""scenario: the force error over a whole turn at the default setting (the regulariser scaled by
1e-8, time constant 128 steps, the solver run to no improvement: adapters.mujoco.mjcf.Physics) and
with MuJoCo's own regulariser at 4 steps, measured, held two-sided (tests.support.bounds)."""
EXUDYN_FORCES: dict[tuple[str, str], float] = {
    key: value for key, (value,) in measured_table("exudyn_forces").items()
}
"""(scenario, mode at the default step): the force error over a whole turn, measured
(GA3 after its run-in), held two-sided (tests.support.bounds)."""
A02_SPEC = (5.36e-09, 1.92e-11, 1.69e-07)
"""n_four_bar/spec (40 loops, 20 s, 20 singular passages) at h = 2e-5 on 400 output steps and the
passage times, on the compiled step: energy drift over the largest kinetic energy, the largest
rocker-to-crank angle (at a passage: 6.4e-12 to 1.9e-11 over the 20; 2.5e-13 at every other output),
the crank's distance to the reduced equation. Measured with the steps near each passage careful
and the step across it placed (dynamics.passage)."""
