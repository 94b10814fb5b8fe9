"""analysis.assemble's round-off refusal for a mechanism whose coordinates are all below 1 (m and
rad): the largest coordinate it names is the mechanism's own, not a floor of 1 (a tolerance below
the round-off reaches this branch directly, where only a mechanism too small to pass the mobility
check would otherwise)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import scenarios
from reference_solver.analysis import assemble
from reference_solver.errors import AssemblyError
from reference_solver.system import ConstraintSystem

FLOORED = re.compile(
    r"slider_crank: the mechanism cannot assemble at t=0: Newton-Raphson stopped with the constraints "
    r"missing by up to (?P<miss>\S+), above the tolerance 1e-16, where C_q is regular: the round-off of "
    r"coordinates as large as (?P<largest>\S+) is about (?P<floor>\S+) \(relative to the characteristic "
    r"length 0\.2\)"
)


def test_a_round_off_refusal_names_the_largest_coordinate_below_one() -> None:
    """The slider-crank (crank r = 0.2 m at theta0 = 0.3 rad, rod l = 0.4 m, L = 0.2 m) assembled to a
    tolerance of 1e-16, below its rows' round-off (a coordinate of 0.59 m sums to C with a spacing of
    floats of 1.1e-16 m, 5.6e-16 of L): Newton stops on the floor (measured 1.4e-16, within ten
    tolerances) with C_q regular. Its largest coordinate is the slider's x, r cos(theta0) +
    sqrt(l^2 - r^2 sin(theta0)^2) = 0.587 m by hand, every other below 0.4."""
    scenario = scenarios.build("slider_crank")
    system = ConstraintSystem(scenario)
    crank, rod, theta0 = 0.2, 0.4, 0.3
    slider_x = crank * math.cos(theta0) + math.sqrt(rod**2 - (crank * math.sin(theta0)) ** 2)
    with pytest.raises(AssemblyError) as caught:
        assemble(system, system.layout.initial_guess(scenario), 0.0, 1e-16)
    match = FLOORED.fullmatch(str(caught.value))
    assert match is not None, str(caught.value)
    assert caught.value.rank_deficiency == 0
    q = caught.value.q
    assert q is not None
    miss = np.max(np.abs(system.residual(q, 0.0) / system.row_scales))
    assert 1e-16 < miss <= 1e-15 and float(match["miss"]) == pytest.approx(miss, rel=1e-2)
    assert float(match["largest"]) == pytest.approx(slider_x, rel=1e-3) and slider_x < 1.0
    assert float(match["floor"]) == pytest.approx(np.finfo(float).eps * slider_x / 0.2, rel=1e-2)
